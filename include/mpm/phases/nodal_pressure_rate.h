#ifndef mpm_phases_nodal_pressure_rate_h
#define mpm_phases_nodal_pressure_rate_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/grid/nodal_vector.h>
#include <mpm/transfer/phase_kernel.h>

#include <functional>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The pore pressure's update with the volumetric rate averaged at the
   * nodes ('Pore water/Pressure rate averaging = node'; PoreWater owns
   * it): after PoreWater's grid-to-particle pass has left each saturated
   * point's own rate r_p = (1 - n) div v_s + n div v_w of this step in a
   * slot,
   *
   *  1. the particle-to-grid pass (ParticleGridWeights::map_phase())
   *     sums sum_p N_ip V_p r_p at the nodes (sum_p N_ip V_p is the
   *     water's own, from its pass of the step: the same points, weights
   *     and volumes);
   *  2. compute_nodal_rates() divides them: R_i, the volume-weighted mean
   *     rate of the points around node i;
   *  3. the grid-to-particle pass (update_phase_points()) changes each
   *     point's pressure by dp = -dt (K_w / n) sum_i N_ip R_i, and the
   *     pressure projection, if any, fits the cell's pressures.
   *
   * The rate a point takes is so continuous, linear over a cell on linear
   * weights: the pressure's increments keep slopes within each cell. With
   * the cell's mean rate ('cell') the increments are a staircase of cell
   * means and the slopes within cells stay those of the start, so that a
   * suction gradient near a drained surface lives only in the jumps
   * between cells, first order in h (doc/pore_water.md, 'Pressure
   * stabilisation'). The rate is this step's, from the end-of-step
   * velocities as the point's own: a rate lagged by a step (summed in the
   * next step's particle-to-grid pass) is a forward Euler step of the
   * undrained wave and blows up at once.
   */
  template <int dim>
  class NodalPressureRate : public PhaseKernel<dim>
  {
  public:
    using typename PhaseKernel<dim>::Targets;
    using typename PhaseKernel<dim>::Sources;
    using typename PhaseKernel<dim>::Sums;
    using typename PhaseKernel<dim>::VertexValues;

    /// Where a point keeps the data the kernel reads and writes.
    struct Slots
    {
      /// The point's own volumetric rate r_p, written by PoreWater.
      unsigned int rate;
      unsigned int pressure;
      /// The porosity n; 0 for a dry point, which the kernel skips.
      unsigned int porosity;
    };

    /// A cell's points together after their update: their properties,
    /// positions and the cell's volume (PoreWater::finish_cell()).
    using CellFinish = std::function<void(const ArrayView<double *const> &,
                                          const ArrayView<const Point<dim>> &,
                                          const double)>;

    /**
     * Registers the kernel's nodal field with @p nodal. @p volume_sums:
     * sum_p N_ip V_p over the saturated points, in every component, as
     * the water's particle-to-grid pass of the step leaves it.
     * @p bulk_modulus: the water's K_w. @p finish: what the water does
     * with a cell's pressures after their update (the projection, the
     * drained free surface), or empty for nothing.
     */
    void
    initialize(NodalFields       &nodal,
               const NodalVector &volume_sums,
               const double       bulk_modulus,
               const CellFinish   finish);

    /// Where the points keep their data (known once the point properties
    /// are laid out).
    void
    set_slots(const Slots &point_slots)
    {
      slots = point_slots;
    }

    void
    set_time_step(const double dt)
    {
      time_step = dt;
    }

    /// R_i = sum N V r / sum N V at the nodes @p active_dofs (local
    /// elements), after map_phase() with this kernel.
    void
    compute_nodal_rates(const std::vector<unsigned int> &active_dofs);

    /// @name PhaseKernel.
    /// @{
    Targets
    grid_targets() override
    {
      return {{&rate_sums}};
    }

    /// N V r of a saturated point, in every component.
    void
    add_to_grid(const double                *props,
                const Q1ShapeFunctions<dim> &sf,
                const VertexValues          &offsets,
                Sums                        &sums) const override;

    /// The nodal rates R_i (after compute_nodal_rates()).
    Sources
    grid_sources() override
    {
      return {{&rate_sums, nullptr, nullptr}};
    }

    /// dp = -dt (K_w / n) sum_i N_i R_i.
    void
    update_point(
      double                                                          *props,
      const std::array<Tensor<1, dim>, PhaseKernel<dim>::max_sources> &values,
      const std::array<Tensor<2, dim>, PhaseKernel<dim>::max_sources> &,
      const Tensor<2, dim> &) const override;

    /// With a projection or a drained free surface: then finish_cell()
    /// applies it.
    bool
    averages_over_cells() const override
    {
      return static_cast<bool>(finish_pressures);
    }

    void
    finish_cell(const ArrayView<double *const>    &props,
                const ArrayView<const Point<dim>> &positions,
                const double                       cell_volume) const override
    {
      if (finish_pressures)
        finish_pressures(props, positions, cell_volume);
    }
    /// @}

  private:
    Slots          slots{0, 0, 0};
    double         bulk_modulus = 0;
    double         time_step    = 0;
    CellFinish         finish_pressures;
    const NodalVector *volume_sums = nullptr;

    /// sum N V r, then R (compute_nodal_rates()), in every component.
    NodalVector rate_sums;
  };
} // namespace MPM

#endif
