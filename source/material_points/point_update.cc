#include <mpm/material_points/point_update.h>
#include <mpm/material_points/property_layout.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace MPM
{
  template <int dim>
  PointUpdate<dim>::PointUpdate(const MaterialLibrary             &materials,
                                const VelocityTransfer<dim>       &transfer,
                                PointRelocation<dim>              &relocation,
                                const TimeSteppingParameters<dim> &time_stepping)
    : materials(materials)
    , transfer(transfer)
    , relocation(relocation)
    , time_stepping(time_stepping)
  {}


  template <int dim>
  void
  PointUpdate<dim>::advance(
    typename Particles::ParticleHandler<dim>::particle_iterator point,
    double                                                   *props,
    const Tensor<1, dim>                                     &a,
    const Tensor<1, dim>                                     &v_new,
    const BilinearCellMap                                    *map,
    Findings                                                 &findings) const
  {
    using Layout      = PropertyLayout<dim>;
    const double dt   = time_step;
    for (unsigned int c = 0; c < dim; ++c)
      {
        double &v = props[Layout::velocity + c];
        v         = flip * (v + dt * a[c]) + (1 - flip) * v_new[c];
      }
    // As one Tensor expression: built component by component, the new
    // position is stored as two scalars and read back as one 16-byte
    // value for set_location(), a store-forwarding stall measured at a
    // tenth of this loop.
    const Point<dim> x = point->get_location() + dt * v_new;
    point->set_location(x);
    // Step 1 of the point location, with each new position at hand.
    if (relocation.can_locate_while_moving())
      PointRelocation<dim>::locate_in_cell(*map, point, x, findings.located);
    const double speed2 =
      read_vector<dim>(&props[Layout::velocity]).norm_square();
    findings.v_max2 = std::max(findings.v_max2, speed2);
    // Blow-up check at the price of one sum: a NaN or infinity in the
    // velocity, position or stress makes it non-finite.
    double check = speed2 + x[0] + x[dim - 1];
    for (unsigned int c = 0; c < 6; ++c)
      check += props[Layout::stress + c];
    if (!std::isfinite(check) && findings.first_bad_point.empty())
      {
        std::ostringstream s;
        s << "material point " << point->get_id() << " at ("
          << point->get_location() << ") in cell "
          << point->get_surrounding_cell()->id().to_string()
          << " has a non-finite velocity, position or stress";
        findings.first_bad_point = s.str();
      }
  }


  template <int dim>
  double
  PointUpdate<dim>::record(Findings &findings)
  {
    if (bad_point.empty())
      bad_point = findings.first_bad_point;
    max_state_wave_speed2 =
      std::max(max_state_wave_speed2, findings.max_state_wave_speed2);
    relocation.add_located(findings.located);
    n_volume_bounded_updates += findings.n_volume_bounded;
    const double v_max2 = findings.v_max2;
    findings            = Findings();
    return v_max2;
  }


  template <int dim>
  double
  PointUpdate<dim>::update_stress(double               *props,
                                  const Tensor<2, dim> &grad_v,
                                  const double          cell_size,
                                  Findings             &findings) const
  {
    using Layout               = PropertyLayout<dim>;
    const double       dt      = time_step;
    const unsigned int n_state = materials.max_n_state_variables();
    const Material &material =
      materials[static_cast<unsigned int>(props[Layout::material_id])];
    double *const               stress = &props[Layout::stress];
    const SymmetricTensor<2, 3> strain_increment =
      materials.update_stored_stress<dim>(
        material,
        grad_v,
        dt,
        stress,
        ArrayView<double>(props + Layout::state, n_state),
        cell_size);
    // The stiffness at the end of this step is the one of the next step's
    // time step. Only for such materials: the others pay one branch.
    if (material.state_dependent_stiffness)
      findings.max_state_wave_speed2 =
        std::max(findings.max_state_wave_speed2,
                 material.model->p_wave_modulus(
                   read_symmetric_tensor(stress),
                   ArrayView<const double>(props + Layout::state, n_state)) /
                   material.density);
    write_symmetric_tensor(read_symmetric_tensor(&props[Layout::strain]) +
                             strain_increment,
                           &props[Layout::strain]);
    // Volume follows the determinant of the incremental deformation
    // gradient I + dt grad v.
    double &volume = props[Layout::volume];
    volume *= determinant(unit_symmetric_tensor<dim>() + dt * grad_v);
    // The material's loosest state bounds the volume (a branch for the
    // materials without a bound).
    if (material.minimum_density > 0)
      {
        const double largest = props[Layout::mass] / material.minimum_density;
        if (volume > largest)
          {
            const double factor = largest / volume;
            volume              = largest;
            ++findings.n_volume_bounded;
            update_porosity(props, material);
            return factor;
          }
      }
    update_porosity(props, material);
    return 1.;
  }


  template <int dim>
  void
  PointUpdate<dim>::update_porosity(double         *props,
                                    const Material &material) const
  {
    if (porosity_slot == numbers::invalid_unsigned_int ||
        material.porosity == 0)
      return;
    using Layout = PropertyLayout<dim>;
    const double grains =
      (1 - material.porosity) * props[Layout::mass] / material.density;
    // Bounded away from 0 and 1, where the formulation has no meaning.
    props[porosity_slot] =
      std::clamp(1 - grains / props[Layout::volume], 1e-3, 1 - 1e-3);
  }


  template <int dim>
  void
  PointUpdate<dim>::average_volumetric_part(double *const     *props,
                                            Tensor<2, dim>     *grad_v,
                                            const unsigned int n)
  {
    using Layout  = PropertyLayout<dim>;
    double volume = 0, trace = 0;
    for (unsigned int q = 0; q < n; ++q)
      {
        const double V = props[q][Layout::volume];
        volume += V;
        trace += V * dealii::trace(grad_v[q]);
      }
    if (!(volume > 0))
      return;
    set_volumetric_part(grad_v, n, trace / volume);
  }


  template <int dim>
  void
  PointUpdate<dim>::set_volumetric_part(Tensor<2, dim>    *grad_v,
                                        const unsigned int n,
                                        const double       mean)
  {
    for (unsigned int q = 0; q < n; ++q)
      {
        const double shift = (mean - dealii::trace(grad_v[q])) / dim;
        for (unsigned int d = 0; d < dim; ++d)
          grad_v[q][d][d] += shift;
      }
  }


  template class PointUpdate<2>;
  template class PointUpdate<3>;
} // namespace MPM
