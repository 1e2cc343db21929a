#ifndef mpm_solver_time_stepping_h
#define mpm_solver_time_stepping_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <mpm/solver/step_scheme.h>

#include <memory>
#include <string>

namespace MPM
{
  /**
   * The time from which a run counts as at its end time @p end_time (a
   * relative 1e-12 before it): the steps' lengths need not add up to the
   * end time exactly. Every comparison with the end time goes through it.
   */
  inline double
  effective_end_time(const double end_time)
  {
    return end_time * (1 - 1e-12);
  }

  using namespace dealii;

  /**
   * Parameters of the explicit time integration ("Time stepping" in the
   * parameter file), parsed once into plain members so the solver never
   * touches the ParameterHandler.
   */
  template <int dim>
  struct TimeSteppingParameters
  {
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    double         end_time = 1;

    /**
     * Whether @p time has reached the end time: to within a relative
     * 1e-12, since the steps' lengths need not add up to it exactly (the
     * last step lands on it, compute_time_step(), up to round-off).
     */
    bool
    reached_end(const double time) const
    {
      return time >= effective_end_time(end_time);
    }
    bool           adaptive = true;
    double         fixed_time_step = 1e-4;
    double         cfl_number      = 0.5;
    double         maximum_time_step = 1e100;
    /// 'Update scheme': the order of a step's operations.
    std::shared_ptr<const StepScheme> step_scheme;
    /// 'Local damping' if it is a number (else its value at t = 0).
    double         local_damping  = 0;
    /// 'Local damping' if it is a function of time, else null.
    std::shared_ptr<const FunctionParser<1>> local_damping_function;
    std::string                              local_damping_expression = "0";

    /**
     * The local damping coefficient of the step that starts at @p time;
     * an InputError if a function of time leaves [0, 1).
     */
    double
    local_damping_at(const double time) const;

    void
    check_local_damping(const double alpha, const double time) const;
    /// 'Volumetric strain averaging': none; each point's volumetric strain
    /// rate replaced by the volume-weighted mean over the points of its
    /// cell (anti-locking); or the cells' means averaged again over the
    /// cells around each of their vertices
    /// (ParticleGridPasses::patch_mean_rates()).
    enum class VolumetricStrainAveraging
    {
      none,
      cell,
      patch
    };
    VolumetricStrainAveraging volumetric_strain_averaging =
      VolumetricStrainAveraging::cell;
    /// 'Gravity' as given, in the scene's frame (as the regions are).
    Tensor<1, dim> scene_gravity;
    /// Gravity in the mesh's frame, which the step works in
    /// (BackgroundGrid::to_mesh_frame()): set once by the Simulator's
    /// set-up, as soon as the mesh exists and before anything reads it.
    Tensor<1, dim> gravity;
  };
} // namespace MPM

#endif
