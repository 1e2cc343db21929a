#ifndef mpm_solver_time_step_bounds_h
#define mpm_solver_time_step_bounds_h

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <functional>
#include <utility>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * What limits the explicit step: each component that carries a wave (the
   * materials' P waves, the pore water's fast wave of the two phases)
   * contributes the fastest speed it carries, and the CFL condition
   * dt = CFL h_min / (c + |v|_max) takes c as the largest of them
   * (Simulator::compute_time_step()). A component adds itself once, at
   * set-up (Simulator::setup_time_step_bounds()), as a function that the
   * step calls at its start: a bound that depends on the points' state (a
   * pressure-dependent stiffness) reads that state there. The step knows
   * no component by name.
   */
  class TimeStepBounds
  {
  public:
    /// The wave speed (m/s) a component carries at the start of a step.
    using WaveSpeed = std::function<double()>;

    /// Forget every bound (before a new set-up).
    void
    clear()
    {
      bounds.clear();
    }

    /// Add a bound whose speed is @p wave_speed.
    void
    add(WaveSpeed wave_speed)
    {
      bounds.push_back(std::move(wave_speed));
    }

    /// The largest wave speed of all bounds (m/s): c of the CFL condition.
    double
    max_wave_speed() const
    {
      Assert(!bounds.empty(), ExcMessage("No time-step bound was added."));
      double c = 0;
      for (const auto &bound : bounds)
        c = std::max(c, bound());
      return c;
    }

  private:
    std::vector<WaveSpeed> bounds;
  };
} // namespace MPM

#endif
