#include <mpm/material_points/property_layout.h>
#include <mpm/phases/nodal_pressure_rate.h>

namespace MPM
{
  template <int dim>
  void
  NodalPressureRate<dim>::initialize(NodalFields       &nodal,
                                     const NodalVector &water_volume_sums,
                                     const double       K_w,
                                     const CellFinish   cell_finish)
  {
    volume_sums  = &water_volume_sums;
    bulk_modulus = K_w;
    finish_pressures = cell_finish;
    nodal.add(rate_sums, NodalFields::Ghosts::summed);
  }


  template <int dim>
  void
  NodalPressureRate<dim>::compute_nodal_rates(
    const std::vector<unsigned int> &active_dofs)
  {
    // Every rank divides its own copies, ghosts included, of the sums
    // map_phase() has summed over the ranks.
    for (const unsigned int i : active_dofs)
      {
        const double V = volume_sums->local_element(i);
        rate_sums.local_element(i) =
          V > 0 ? rate_sums.local_element(i) / V : 0.;
      }
  }


  template <int dim>
  void
  NodalPressureRate<dim>::add_to_grid(const double                *props,
                                      const Q1ShapeFunctions<dim> &sf,
                                      const VertexValues &,
                                      Sums &sums) const
  {
    if (props[slots.porosity] == 0)
      return;
    const double V = props[PropertyLayout<dim>::volume];
    const double r = props[slots.rate];
    for (unsigned int i = 0; i < PhaseKernel<dim>::n_vertices; ++i)
      {
        const double NVr = sf.value[i] * V * r;
        for (unsigned int c = 0; c < dim; ++c)
          {
            sums[0][i][c] += NVr;
          }
      }
  }


  template <int dim>
  void
  NodalPressureRate<dim>::update_point(
    double                                                          *props,
    const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
    const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> &,
    const Tensor<2, dim> &) const
  {
    // The porosity of the step's start, as PoreWater's own update uses
    // (the skeleton's stress update, later in the step, moves it with the
    // volume).
    const double n = props[slots.porosity];
    if (n == 0)
      return;
    props[slots.pressure] -= time_step * bulk_modulus / n * values[0][0];
  }


  template class NodalPressureRate<2>;
  template class NodalPressureRate<3>;
} // namespace MPM
