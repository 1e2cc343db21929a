#ifndef mpm_solver_rest_criterion_h
#define mpm_solver_rest_criterion_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * Ends a run before 'Time stepping/End time' once the material has come
   * to rest ('Termination/Stop at rest'): when the points' speed, by
   * 'Rest measure', has stayed below 'Rest speed' over 'Rest duration' of
   * simulated time.
   *
   * Why: a runout scene (a collapse, a landslide, the flume) is run to an
   * end time guessed to lie after the deposit stops, and the steps after
   * that are creep at a small fraction of the flow's speed: half the
   * steps of the column collapse at a = 4 (at rest from 0.69 s, run to
   * 1.6 s). The criterion lets the end time be a generous bound.
   *
   * Three measures, taken at the end of each step:
   *  - the root mean square speed, sqrt(sum m v^2 / sum m) (the default):
   *    the kinetic energy per mass: one more loop over the points (their
   *    mass and velocity, 32 of the about 750 bytes a 2D step reads and
   *    writes per point) and one reduction per step. A settled granular
   *    deposit keeps a few points creeping at the front (the column
   *    collapse at a = 0.5: the mean speed is below 1e-4 m/s from 0.7 s
   *    on, and the front point still moves 0.8 mm in the 0.5 s after);
   *    the mass-weighted measure lets such a deposit stop. A point thrown
   *    out of the flow at speed keeps it going (the collapse at a = 6 on
   *    1.25 mm: one point at about 3 m/s holds the rms speed at 5-8 mm/s
   *    while the mean speed is 1e-4 m/s).
   *  - the mean speed, sum m |v| / sum m: the same loop; a point's weight
   *    grows with its speed, not with its square, so a few thrown points
   *    weigh little (the point above adds 2e-5 m/s to it, against 8e-3 m/s
   *    to the rms speed), and so do a few creeping ones, and so does a
   *    small flowing part beside a large static one: the a = 0.5 column
   *    collapse (only its corner slumps) stops at 0.367 s instead of
   *    0.740 s, its front point 7 % short of the rms run's, the runout
   *    of 95 % of its volume 0.3 % (test
   *    column_collapse_stop_at_rest_mean_speed).
   *  - the largest point speed: free (the grid-to-particle pass reduces it
   *    over all points and ranks for the next time step), and strict: one
   *    creeping point keeps the run going, so a deposit whose front creeps
   *    runs to its end time, as without the criterion.
   *
   * The criterion knows nothing of what the scene does later: a run that
   * stands still until a trigger (a strength reduction or a boundary
   * motion that starts later) needs 'Earliest stop time' after that
   * trigger.
   */
  class RestCriterion
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /// What 'Rest measure' compares with 'Rest speed'.
    enum class Measure
    {
      root_mean_square_speed,
      mean_speed,
      largest_speed
    };

    /// Whether the run is to be checked at all ('Stop at rest').
    bool
    enabled() const
    {
      return stop_at_rest;
    }

    Measure
    measure() const
    {
      return rest_measure;
    }

    /**
     * After each step: the time at its end, @p time, and the points' speed
     * then by measure(), @p speed.
     */
    void
    update(const double time, const double speed);

    /// Whether the run is to stop: the material is at rest.
    bool
    at_rest() const
    {
      return stopped;
    }

    /**
     * What the report and the screen say when the run stopped at rest: the
     * criterion and the time from which the points stayed below the rest
     * speed.
     */
    std::string
    description(const double time, const double end_time) const;

    /**
     * The state a checkpoint keeps (the time from which the points have
     * stayed below the rest speed, if they have), so that a resumed run
     * stops at the step the uninterrupted one would. (No checkpoint is
     * written at the step that stops the run.)
     */
    template <class Archive>
    void
    serialize(Archive &ar, const unsigned int /*version*/)
    {
      ar &below_since;
    }

  private:
    bool    stop_at_rest  = false;
    Measure rest_measure  = Measure::root_mean_square_speed;
    double  rest_speed    = 1e-3;
    double  rest_duration = 0.1;
    double  earliest_stop = 0;
    /// Time at the end of the first step of the current stretch of steps
    /// below the rest speed; negative if the last step was above it.
    double  below_since   = -1;
    bool    stopped       = false;
  };
} // namespace MPM

#endif
