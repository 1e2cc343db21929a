#ifndef mpm_material_points_point_update_h
#define mpm_material_points_point_update_h

#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/grid/bilinear_cell_map.h>
#include <mpm/material_points/point_relocation.h>
#include <mpm/materials/material_library.h>
#include <mpm/solver/time_stepping.h>
#include <mpm/transfer/velocity_transfer.h>

#include <cmath>
#include <cstdint>
#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * What happens to one material point once the grid's values have been
   * interpolated to it, the same whatever the particle-grid weights
   * (ParticleGridWeights): its new velocity and position (grid to
   * particle), and its strain, stress and volume from a velocity gradient
   * (the stress update). The weights decide how the interpolation is
   * done and call these for each point in their own order.
   */
  template <int dim>
  class PointUpdate
  {
  public:
    /// The objects are the Simulator's, read when the points are updated
    /// (so they may be parsed after construction).
    PointUpdate(const MaterialLibrary              &materials,
                const VelocityTransfer<dim>        &transfer,
                PointRelocation<dim>               &relocation,
                const TimeSteppingParameters<dim>  &time_stepping);

    /// The step's time step (and with it the FLIP fraction), set before
    /// the step's passes.
    void
    set_time_step(const double dt)
    {
      time_step = dt;
      flip      = transfer.scheme().flip_fraction(dt);
    }

    /**
     * The slot of the pore water's porosity (PoreWater::porosity_slot()),
     * set when the scene has pore water: a saturated point's porosity then
     * follows its volume where update_stress() changes it. Its grains keep
     * their volume, (1 - n) V = (1 - n0) V0 with V0 = m / rho_d, so
     * n = 1 - (1 - n0) m / (rho_d V): the porosity, the volume and the
     * water the pores hold stay one state, whatever rate the volume took
     * ('Volumetric strain averaging', 'Minimum density').
     */
    void
    set_porosity_slot(const unsigned int slot)
    {
      porosity_slot = slot;
    }

    /**
     * What the updates of a range of points found: kept per chunk of points
     * by the threaded passes (for_each_chunk()), so that the points update
     * concurrently, and handed to record() in chunk order.
     */
    struct Findings
    {
      /// The largest squared point speed after advance().
      double v_max2 = 0;
      /// The largest squared P-wave speed after update_stress() of points
      /// whose material's stiffness depends on the state.
      double max_state_wave_speed2 = 0;
      /// The first point found with a non-finite velocity, position or
      /// stress (empty if none).
      std::string first_bad_point;
      /// Stress updates that kept a point's volume at its material's
      /// 'Minimum density'.
      std::uint64_t n_volume_bounded = 0;
      /// Step 1 of the point location, if done while moving.
      typename PointRelocation<dim>::Located located;
    };

    /**
     * Grid to particle for one point (@p point, its properties @p props):
     * its new velocity from the interpolated nodal acceleration @p a and
     * end-of-step velocity @p v_new (the FLIP/PIC blend of the
     * VelocityTransfer), its new position x + dt v_new (located in its
     * cell, whose 2D map is @p map, if the relocation does that while
     * moving), its speed and the blow-up check into @p findings. Safe on
     * several threads for different points and findings.
     */
    void
    advance(typename Particles::ParticleHandler<dim>::particle_iterator point,
            double                                                   *props,
            const Tensor<1, dim>                                     &a,
            const Tensor<1, dim>                                     &v_new,
            const BilinearCellMap                                    *map,
            Findings &findings) const;

    /// One point's strain, stress (its material model) and volume from
    /// its velocity gradient @p grad_v over the time step, in a background
    /// cell of size @p cell_size (BackgroundGrid::cell_size(); for a model
    /// regularised by it). For a material whose stiffness depends on the
    /// state, the point's new P-wave speed enters @p findings. Safe on
    /// several threads for different points and findings.
    ///
    /// Returns the factor by which the point's volume was reduced below
    /// V_p det(I + dt grad v) to keep it at most m_p over its material's
    /// 'Minimum density' (1 if it was not), for the weights' own data
    /// (CPDI's domain) to follow.
    double
    update_stress(double               *props,
                  const Tensor<2, dim> &grad_v,
                  const double          cell_size,
                  Findings             &findings) const;

    /**
     * Take over what the updates of a range of points found (the ranges in
     * the order of the points): the first bad point, the state's wave
     * speed, the point location's step 1. Resets @p findings; returns its
     * v_max2.
     */
    double
    record(Findings &findings);

    /**
     * The largest P-wave speed, after their stress update, of this rank's
     * points whose material's stiffness depends on the state (0 if none),
     * since the last call; resets it. The next step's time step needs it.
     */
    double
    take_max_state_wave_speed()
    {
      const double c = std::sqrt(max_state_wave_speed2);
      max_state_wave_speed2 = 0;
      return c;
    }

    /// Whether the points of a cell share their volumetric strain rate
    /// ('Time stepping/Volumetric strain averaging = cell' or 'patch'): then
    /// the weights call average_volumetric_part() on each cell's gradients
    /// before update_stress().
    bool
    averages_volumetric_strain() const
    {
      return time_stepping.volumetric_strain_averaging !=
             TimeSteppingParameters<dim>::VolumetricStrainAveraging::none;
    }

    /// Whether the cells' means are averaged again over the cells around
    /// each vertex ('Volumetric strain averaging = patch').
    bool
    averages_volumetric_strain_over_patches() const
    {
      return time_stepping.volumetric_strain_averaging ==
             TimeSteppingParameters<dim>::VolumetricStrainAveraging::patch;
    }

    /**
     * Set the traces of the velocity gradients @p grad_v of @p n points to
     * @p mean, keeping the deviatoric parts.
     */
    static void
    set_volumetric_part(Tensor<2, dim>    *grad_v,
                        const unsigned int n,
                        const double       mean);

    /**
     * Replace the trace of the velocity gradients @p grad_v of @p n points
     * (properties @p props) by their volume-weighted mean, keeping the
     * deviatoric parts (anti-locking).
     */
    static void
    average_volumetric_part(double *const     *props,
                            Tensor<2, dim>     *grad_v,
                            const unsigned int n);

    /// Stress updates on this rank, since the start of this invocation,
    /// that kept a point's volume at its material's 'Minimum density'.
    std::uint64_t
    n_volume_bounded() const
    {
      return n_volume_bounded_updates;
    }

    /// Description of the first point found non-finite, empty if none.
    const std::string &
    first_bad_point() const
    {
      return bad_point;
    }

  private:
    const MaterialLibrary       &materials;
    const VelocityTransfer<dim> &transfer;
    PointRelocation<dim>        &relocation;
    const TimeSteppingParameters<dim> &time_stepping;
    double                       time_step = 0;
    double                       flip      = 0;
    std::string                  bad_point;
    /// The square of take_max_state_wave_speed().
    double                       max_state_wave_speed2 = 0;
    std::uint64_t                n_volume_bounded_updates = 0;
    /// set_porosity_slot(); invalid: no pore water.
    unsigned int porosity_slot = numbers::invalid_unsigned_int;

    /// The porosity of a saturated point from its volume
    /// (set_porosity_slot()); nothing for a dry one.
    void
    update_porosity(double *props, const Material &material) const;
  };
} // namespace MPM

#endif
