// The Simulator's diagnostics: sums over the points (mass, momentum,
// energies, angular momentum) for the statistics file and the
// postprocessors, and the detection of a run that became unstable.

#include <deal.II/base/mpi.h>

#include <mpm/material_points/property_layout.h>
#include <mpm/solver/simulator.h>

#include <limits>
#include <sstream>

namespace MPM
{
  template <int dim>
  void
  Simulator<dim>::set_max_point_speed(const double v_max2)
  {
    // A bad point makes the largest speed infinite on every rank: the
    // reduction that exists anyway tells all ranks to stop.
    max_point_speed = Utilities::MPI::max(
      point_update.first_bad_point().empty() ? std::sqrt(v_max2) :
                                std::numeric_limits<double>::infinity(),
      mpi_communicator);
    // For the next step's time step.
    max_point_speed_step = step + 1;
    if (!std::isfinite(max_point_speed))
      stop_on_blow_up("a value became infinite or NaN.", true);
  }


  template <int dim>
  double
  Simulator<dim>::point_speed(const RestCriterion::Measure measure) const
  {
    if (measure == RestCriterion::Measure::largest_speed)
      // Reduced by the grid-to-particle pass for the next step.
      return max_point_speed;
    using Layout = PropertyLayout<dim>;
    const bool   root_mean_square =
      measure == RestCriterion::Measure::root_mean_square_speed;
    Tensor<1, 2> mass_and_weighted_speed;
    for (const auto &point : particle_handler)
      {
        const auto           props = point.get_properties();
        const Tensor<1, dim> v     = read_vector<dim>(&props[Layout::velocity]);
        mass_and_weighted_speed[0] += props[Layout::mass];
        mass_and_weighted_speed[1] +=
          props[Layout::mass] * (root_mean_square ? v.norm_square() : v.norm());
      }
    mass_and_weighted_speed =
      Utilities::MPI::sum(mass_and_weighted_speed, mpi_communicator);
    if (!(mass_and_weighted_speed[0] > 0))
      return 0.;
    const double mean = mass_and_weighted_speed[1] / mass_and_weighted_speed[0];
    return root_mean_square ? std::sqrt(mean) : mean;
  }


  template <int dim>
  double
  Simulator<dim>::compute_max_state_wave_speed() const
  {
    using Layout               = PropertyLayout<dim>;
    const unsigned int n_state = materials.max_n_state_variables();
    double             c       = 0;
    for (const auto &point : particle_handler)
      {
        const auto      props = point.get_properties();
        const Material &material =
          materials[static_cast<unsigned int>(props[Layout::material_id])];
        if (material.state_dependent_stiffness)
          c = std::max(c,
                       material.wave_speed(
                         read_symmetric_tensor(&props[Layout::stress]),
                         ArrayView<const double>(&props[Layout::state],
                                                 n_state)));
      }
    return Utilities::MPI::max(c, mpi_communicator);
  }


  template <int dim>
  void
  Simulator<dim>::stop_on_blow_up(const std::string &reason,
                                  const bool         during_step)
  {
    using Layout = PropertyLayout<dim>;
    // Which point: the first bad one, or else the fastest.
    std::string here = point_update.first_bad_point();
    if (here.empty())
      {
        double fastest = -1;
        for (const auto &point : particle_handler)
          {
            const auto v =
              read_vector<dim>(&point.get_properties()[Layout::velocity]);
            if (v.norm() > fastest)
              {
                fastest = v.norm();
                std::ostringstream s;
                s << "the fastest material point, " << point.get_id()
                  << " at (" << point.get_location() << ") in cell "
                  << point.get_surrounding_cell()->id().to_string()
                  << ", moves at " << v.norm() << " m/s";
                here = s.str();
              }
          }
        const double global = Utilities::MPI::max(fastest, mpi_communicator);
        if (fastest < global)
          here.clear();
      }
    // The grid-to-particle check stops inside a step, the energy check
    // after it.
    std::ostringstream when_stream;
    if (during_step)
      when_stream << "in step " << step + 1 << " (from t = " << time
                  << " s to " << time + time_step << " s)";
    else
      when_stream << "by step " << step << " (t = " << time << " s)";
    const std::string when = when_stream.str();
    std::string       point_description;
    for (const auto &d : Utilities::MPI::all_gather(mpi_communicator, here))
      if (!d.empty())
        {
          point_description = d;
          break;
        }
    write_output(true);
    throw std::runtime_error(
      "The run became unstable " + when + ": " + reason +
      " First: " + point_description +
      ". The state at this step was written to " + output_writer.directory() +
      " (statistics, and the particle files if 'Output/Write particles' is "
      "on). " +
      StabilityMonitor<dim>::advice(time_step,
                                    time_step_bounds.max_wave_speed(),
                                    active_cell_size,
                                    time_stepping.adaptive));
  }


  template <int dim>
  GlobalStatistics<dim>
  Simulator<dim>::compute_statistics() const
  {
    using Layout = PropertyLayout<dim>;
    GlobalStatistics<dim> s;
    // The pore water's mass, its momentum, and the saturated volume and
    // sum V p; for the periodic correction below the water the energies
    // weigh (carried from the start) and the still water displaced.
    double water_mass = 0, saturated_volume = 0, pressure_sum = 0,
           displaced_mass = 0, carried_mass = 0;
    Tensor<1, dim> water_momentum;
    s.time      = time;
    s.time_step = time_step;
    s.step      = step;
    for (const auto &point : particle_handler)
      {
        const auto           props = point.get_properties();
        const double         m     = props[Layout::mass];
        const Tensor<1, dim> v     = read_vector<dim>(&props[Layout::velocity]);
        s.mass += m;
        s.volume += props[Layout::volume];
        s.momentum += m * v;
        const auto energy = energy_of_point(props.data(), point.get_location());
        s.kinetic_energy += energy[0];
        s.strain_energy += energy[1];
        s.gravitational_potential_energy += energy[2];
        s.mean_speed += v.norm();
        s.max_speed = std::max(s.max_speed, v.norm());
        s.centre_of_mass += m * point.get_location();
        if (pore_water.active() && props[pore_water.porosity_slot()] > 0)
          {
            const double m_w = pore_water.water_mass(props.data());
            water_mass += m_w;
            displaced_mass += pore_water.displaced_water_mass(props.data());
            carried_mass += pore_water.carried_water_mass(props.data());
            water_momentum +=
              m_w * read_vector<dim>(&props[pore_water.velocity_slot()]);
            saturated_volume += props[Layout::volume];
            pressure_sum +=
              props[Layout::volume] * props[pore_water.pressure_slot()];
          }
      }
    if (pore_water.active())
      {
        water_mass       = Utilities::MPI::sum(water_mass, mpi_communicator);
        s.water_mass     = water_mass;
        s.water_momentum = Utilities::MPI::sum(water_momentum, mpi_communicator);
        saturated_volume =
          Utilities::MPI::sum(saturated_volume, mpi_communicator);
        s.mean_pore_pressure =
          Utilities::MPI::sum(pressure_sum, mpi_communicator) /
          (saturated_volume > 0 ? saturated_volume : 1);
      }
    s.n_points = particle_handler.n_global_particles();
    s.mass     = Utilities::MPI::sum(s.mass, mpi_communicator);
    s.volume   = Utilities::MPI::sum(s.volume, mpi_communicator);
    s.momentum = Utilities::MPI::sum(s.momentum, mpi_communicator);
    s.kinetic_energy = Utilities::MPI::sum(s.kinetic_energy, mpi_communicator);
    s.strain_energy  = Utilities::MPI::sum(s.strain_energy, mpi_communicator);
    s.gravitational_potential_energy =
      Utilities::MPI::sum(s.gravitational_potential_energy, mpi_communicator);
    // With periodic boundaries: the potential energy and the centre of
    // mass of the points' unwrapped positions, continuous when a point
    // wraps (the points of a sliding infinite slope jump back up by a
    // period's drop when they wrap; the slope goes on releasing energy and
    // its centre of mass goes on moving down).
    Tensor<1, dim> unwrapped_centre_shift;
    if (!grid.periodic_boundaries.empty())
      {
        const Tensor<1, dim> shift = wrapped_mass_shift();
        // The shifts are the skeleton's (PointRelocation); the water
        // wraps with it, taken in the ratio of the water the energies
        // weigh (energy_of_point()) to the skeleton's mass (exact for a
        // uniform saturation).
        const double water_share =
          pore_water.active() && s.mass > 0 ?
            Utilities::MPI::sum(carried_mass, mpi_communicator) / s.mass :
            0.;
        // Submerged: the skeleton's buoyant weight instead.
        const double weight_share =
          pore_water.is_submerged() ?
            1 - (s.mass > 0 ?
                   Utilities::MPI::sum(displaced_mass, mpi_communicator) /
                     s.mass :
                   0.) :
            1 + water_share;
        s.gravitational_potential_energy +=
          weight_share * (time_stepping.gravity * shift);
        unwrapped_centre_shift = shift;
      }
    s.removed_energy = lost_points.totals(mpi_communicator).energy;
    s.mean_speed =
      Utilities::MPI::sum(s.mean_speed, mpi_communicator) /
      std::max<double>(1, s.n_points);
    s.max_speed      = Utilities::MPI::max(s.max_speed, mpi_communicator);
    s.centre_of_mass =
      (Utilities::MPI::sum(s.centre_of_mass, mpi_communicator) -
       unwrapped_centre_shift) /
      (s.mass > 0 ? s.mass : 1);
    s.mean_velocity = s.momentum / (s.mass > 0 ? s.mass : 1);
    return s;
  }


  template <int dim>
  Tensor<1, dim>
  Simulator<dim>::wrapped_mass_shift() const
  {
    return Utilities::MPI::sum(
      point_relocation.statistics().wrapped_mass_shift +
        wrapped_mass_shift_before_restart,
      mpi_communicator);
  }


  template <int dim>
  std::array<double, 3>
  Simulator<dim>::energy_of_point(const double *props, const Point<dim> &x) const
  {
    using Layout             = PropertyLayout<dim>;
    const double      m      = props[Layout::mass];
    const Material   &material =
      materials[static_cast<unsigned int>(props[Layout::material_id])];
    std::array<double, 3> energy{
      {0.5 * m * read_vector<dim>(&props[Layout::velocity]).norm_square(),
       props[Layout::volume] *
         material.model->strain_energy_density(
           read_symmetric_tensor(&props[Layout::stress])),
       -m * (time_stepping.gravity * x)}};
    if (pore_water.active() && props[pore_water.porosity_slot()] > 0)
      {
        // The point's water, n rho_w V: its motion, its compression
        // (n V p^2 / (2 K_w)) and the weight of the water it carried from
        // the start (PoreWater::carried_water_mass(): so that the energy
        // released does not depend on where the coordinates' origin is);
        // submerged, the still water's buoyancy on the skeleton in place
        // of the weight (the water's weight and the hydrostatic pressure
        // cancel).
        const double n   = props[pore_water.porosity_slot()];
        const double V   = props[Layout::volume];
        const double m_w = pore_water.water_mass(props);
        const double p   = props[pore_water.pressure_slot()];
        energy[0] +=
          0.5 * m_w *
          read_vector<dim>(&props[pore_water.velocity_slot()]).norm_square();
        energy[1] += n * V * p * p / (2 * pore_water.get_bulk_modulus());
        if (pore_water.is_submerged())
          energy[2] += pore_water.displaced_water_mass(props) *
                       (time_stepping.gravity * x);
        else
          energy[2] +=
            -pore_water.carried_water_mass(props) * (time_stepping.gravity * x);
      }
    return energy;
  }


  template <int dim>
  std::pair<Tensor<1, 3>, double>
  Simulator<dim>::spin_angular_momentum(
    const Point<dim>     &centre,
    const Tensor<1, dim> &mean_velocity) const
  {
    using Layout     = PropertyLayout<dim>;
    const auto cross = [](const Tensor<1, dim> &a, const Tensor<1, dim> &b) {
      Tensor<1, 3> c;
      if constexpr (dim == 2)
        c[2] = a[0] * b[1] - a[1] * b[0];
      else
        c = cross_product_3d(a, b);
      return c;
    };
    const bool   affine = transfer.scheme().carries_affine_velocity();
    Tensor<1, 3> L;
    double       scale = 0;
    for (const auto &point : particle_handler)
      {
        const auto           props = point.get_properties();
        const double         m     = props[Layout::mass];
        const Tensor<1, dim> r     = point.get_location() - centre;
        const Tensor<1, dim> v =
          read_vector<dim>(&props[Layout::velocity]) - mean_velocity;
        L += m * cross(r, v);
        // With the absolute velocity: not zero for a body in pure
        // translation, whose spin is zero.
        scale += m * r.norm() * (v + mean_velocity).norm();
        if (affine)
          L += m * transfer.scheme().affine_angular_momentum_of_point(
                     &props[transfer_slot]);
      }
    return {Utilities::MPI::sum(L, mpi_communicator),
            Utilities::MPI::sum(scale, mpi_communicator)};
  }


  // The members defined here (the class itself is instantiated in
  // simulator.cc): one explicit instantiation per member, so that
  // the Simulator's files can share one translation unit (unity
  // build) without instantiating the class twice.
#define MPM_INSTANTIATE(dim)                                                 \
  template void   Simulator<dim>::set_max_point_speed(const double);         \
  template double Simulator<dim>::point_speed(const RestCriterion::Measure)  \
    const;                                                                   \
  template double Simulator<dim>::compute_max_state_wave_speed() const;      \
  template void   Simulator<dim>::stop_on_blow_up(const std::string &,       \
                                                const bool);               \
  template GlobalStatistics<dim> Simulator<dim>::compute_statistics() const; \
  template Tensor<1, dim>        Simulator<dim>::wrapped_mass_shift() const; \
  template std::array<double, 3> Simulator<dim>::energy_of_point(            \
    const double *, const Point<dim> &) const;                               \
  template std::pair<Tensor<1, 3>, double>                                   \
  Simulator<dim>::spin_angular_momentum(const Point<dim> &,                  \
                                        const Tensor<1, dim> &) const;

  MPM_INSTANTIATE(2)
  MPM_INSTANTIATE(3)
#undef MPM_INSTANTIATE
} // namespace MPM
