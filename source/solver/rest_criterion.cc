#include <mpm/solver/rest_criterion.h>

#include <algorithm>
#include <sstream>

namespace MPM
{
  void
  RestCriterion::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Termination");
    prm.declare_entry("Stop at rest",
                      "false",
                      Patterns::Bool(),
                      "End the run before 'Time stepping/End time' once the "
                      "points' speed by 'Rest measure' has stayed below "
                      "'Rest speed' for 'Rest duration' of simulated time. "
                      "The output, the statistics and the postprocessors' "
                      "report are written at the time the run stops, and "
                      "the report says so.");
    prm.declare_entry("Rest measure",
                      "root mean square speed",
                      Patterns::Selection(
                        "root mean square speed|mean speed|largest speed"),
                      "'root mean square speed': sqrt(sum m v^2 / sum m) "
                      "over all points, at the end of each step (a few "
                      "points creeping at a deposit's front weigh little; "
                      "a point thrown out of the flow at speed keeps the "
                      "run going); 'mean speed': sum m |v| / sum m (the "
                      "least strict: thrown points weigh less than in the "
                      "rms speed, for a scene that ejects a few, but so "
                      "does a small flowing part beside a large static "
                      "one: the a = 0.5 column collapse stops at 0.37 s "
                      "instead of 0.74 s with its front point 7 % short); "
                      "'largest speed': the fastest point's (strict: one "
                      "creeping point keeps the run going).");
    prm.declare_entry("Rest speed",
                      "1e-3",
                      Patterns::Double(0),
                      "The speed (m/s) below which 'Rest measure' must stay "
                      "for the material to count as at rest.");
    prm.declare_entry("Rest duration",
                      "0.1",
                      Patterns::Double(0),
                      "How long (s of simulated time) 'Rest measure' must "
                      "stay below 'Rest speed' before the run stops.");
    prm.declare_entry("Earliest stop time",
                      "0",
                      Patterns::Double(0),
                      "The run does not stop at rest before this time (s): "
                      "for a scene that stands still until a trigger (a "
                      "strength reduction, a boundary that starts to "
                      "move), set it after the trigger.");
    prm.leave_subsection();
  }


  void
  RestCriterion::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Termination");
    stop_at_rest  = prm.get_bool("Stop at rest");
    const std::string measure = prm.get("Rest measure");
    rest_measure  = measure == "largest speed" ? Measure::largest_speed :
                    measure == "mean speed"    ? Measure::mean_speed :
                                                 Measure::root_mean_square_speed;
    rest_speed    = prm.get_double("Rest speed");
    rest_duration = prm.get_double("Rest duration");
    earliest_stop = prm.get_double("Earliest stop time");
    prm.leave_subsection();
  }


  void
  RestCriterion::update(const double time, const double speed)
  {
    if (!stop_at_rest)
      return;
    if (!(speed < rest_speed))
      {
        below_since = -1;
        return;
      }
    if (below_since < 0)
      below_since = time;
    // Round-off of the summed time steps must not cost a step.
    const double tolerance = 1e-12 * std::max(1., time);
    stopped = time - below_since >= rest_duration - tolerance &&
              time >= earliest_stop - tolerance;
  }


  std::string
  RestCriterion::description(const double time, const double end_time) const
  {
    std::ostringstream out;
    out << "stopped at rest at t = " << time << " s (End time " << end_time
        << " s): "
        << (rest_measure == Measure::largest_speed ? "no point faster than " :
            rest_measure == Measure::mean_speed    ? "mean speed below " :
                                                     "root mean square speed below ")
        << rest_speed << " m/s since t = " << below_since
        << " s (Termination/Rest speed, Rest duration " << rest_duration
        << " s";
    if (earliest_stop > 0)
      out << ", Earliest stop time " << earliest_stop << " s";
    out << ")";
    return out.str();
  }
} // namespace MPM
