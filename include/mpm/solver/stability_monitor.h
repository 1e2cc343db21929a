#ifndef mpm_solver_stability_monitor_h
#define mpm_solver_stability_monitor_h

#include <deal.II/base/parameter_handler.h>

#include <mpm/solver/statistics.h>

#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * Detection of a run that has become unstable, so that it stops with a
   * message that says what to change instead of producing garbage.
   *
   * Two signs are watched:
   *  - a non-finite value (velocity, position or stress of a point), found
   *    in the grid-to-particle loop at no extra cost (the Simulator checks
   *    it every step);
   *  - energy growing without a source: every 'Energy check interval'
   *    steps, the kinetic + strain energy must not exceed 'Energy growth
   *    factor' times the energy the scene can have released, E_available =
   *    (kinetic + strain energy at the start) + (gravitational potential
   *    energy released since). Friction and plasticity only dissipate, so a
   *    stable run stays below 1 x E_available (up to the small energy
   *    errors of MPM); an explicit step above its stability limit grows
   *    exponentially and crosses any factor within steps. Boundaries with
   *    a prescribed velocity do work the check cannot count: with them the
   *    energy check is off (the non-finite check stays).
   */
  template <int dim>
  class StabilityMonitor
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Take the energies at the start of the run; @p external_work tells
     * whether boundaries do work (then the energy check is off).
     */
    void
    initialize(const GlobalStatistics<dim> &start, const bool external_work);

    /**
     * Whether the energy is to be checked after step @p step.
     */
    bool
    energy_check_due(const unsigned int step) const
    {
      return energy_check_on && interval > 0 && step % interval == 0;
    }

    /**
     * An empty string if the energy in @p now is plausible; otherwise what
     * is wrong, with the numbers.
     */
    std::string
    check_energy(const GlobalStatistics<dim> &now) const;

    /**
     * What to change, given the step that was taken: @p time_step, the
     * largest elastic wave speed @p wave_speed, the shortest edge of the
     * cells holding points @p cell_size, and whether the step came from
     * the CFL condition.
     */
    static std::string
    advice(const double time_step,
           const double wave_speed,
           const double cell_size,
           const bool   adaptive);

    /**
     * The energies of the run's start, for a checkpoint: a resumed run
     * checks against the start of the run, not of the resumption (where
     * the scene has released nothing yet, and a run that the uninterrupted
     * one would continue could be stopped, or the reverse).
     */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int /*version*/)
    {
      ar &initial_energy &initial_potential_energy;
    }

  private:
    double       growth_factor   = 10;
    unsigned int interval        = 100;
    bool         energy_check_on = true;
    double       initial_energy  = 0;
    double       initial_potential_energy = 0;
  };
} // namespace MPM

#endif
