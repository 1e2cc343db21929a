#ifndef mpm_boundary_conditions_normal_stress_memory_h
#define mpm_boundary_conditions_normal_stress_memory_h

#include <deal.II/base/parameter_handler.h>

namespace MPM
{
  using namespace dealii;

  /**
   * How the normal force that a frictional wall's Coulomb part takes
   * follows the wall's present normal force: with a memory length L > 0
   * over a slip of about L (Prakash and Clifton's law in the simplified
   * form of Rice, Lapusta and Ranjith 2001),
   *
   *     dN_m/dt = -((|v_t| + V*) / L) (N_m - N),
   *
   * per wall node, integrated by backward Euler (no overshoot whatever the
   * step), with N_m = N where the material first touches the wall; V* makes
   * the memory fade over L / V* at rest. Steady sliding and sticking are
   * Coulomb's (N_m = N); a change of the normal force reaches the friction
   * after a slip of about L.
   *
   * Why: Coulomb friction with a constant coefficient makes the steady
   * sliding of an elastic body dynamically unstable (friction-induced
   * flutter; Adams 1995, Martins, Guimaraes and Faria 1995): a heave of
   * the sliding body changes the normal force, so the friction, so the
   * body's stretching along the wall, so the heave. Measured on a sliding
   * elastic layer (doc/boundary_conditions.md, 'Sliding on Coulomb
   * friction: a flutter'): every transfer that keeps the grid's
   * velocity modes (APIC, FLIP, the blend 0.98) lets it grow, at rates
   * that increase under refinement, and only PIC's damping hides it;
   * L of 1 mm removes it. L = 0 (the default): N_m = N, Coulomb's law as is.
   */
  class NormalStressMemory
  {
  public:
    /// The entries of the boundary subsection that is entered.
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Normal stress memory length",
        "0",
        Patterns::Double(0),
        "For Type = friction: L (m) >= 0, the slip over which the normal "
        "force that the Coulomb part takes follows the wall's present "
        "normal force N: dN_m/dt = -((|v_t| + V*) / L) (N_m - N) per wall "
        "node (Prakash and Clifton's law as simplified by Rice, Lapusta "
        "and Ranjith 2001), N_m = N where the material first touches the "
        "wall; steady sliding and sticking are Coulomb's. 0: N_m = N. "
        "Coulomb friction with a constant coefficient lets the steady "
        "sliding of an elastic body flutter, at rates that grow under "
        "refinement, on every transfer but PIC; L of about a grain "
        "diameter (1 mm in the measured sliding layer) removes it "
        "(doc/boundary_conditions.md, 'Sliding on Coulomb friction: a "
        "flutter').");
      prm.declare_entry(
        "Normal stress memory speed",
        "0.1",
        Patterns::Double(0),
        "V* (m/s) >= 0 of 'Normal stress memory length': at rest the "
        "memory fades over L / V* (10 ms with L = 1 mm), so that a node "
        "that sticks while its load grows takes the new load.");
    }

    /// Read the entries of the boundary subsection that is entered.
    void
    parse_parameters(ParameterHandler &prm)
    {
      length = prm.get_double("Normal stress memory length");
      speed  = prm.get_double("Normal stress memory speed");
    }

    /// Whether N_m differs from N (L > 0).
    bool
    active() const
    {
      return length > 0;
    }

    /**
     * N_m at the end of a step @p dt from its last value @p remembered,
     * the present normal force @p now and the wall node's tangential
     * speed @p slip_speed.
     */
    double
    relax(const double remembered,
          const double now,
          const double slip_speed,
          const double dt) const
    {
      const double beta = dt * (slip_speed + speed) / length;
      return (remembered + beta * now) / (1 + beta);
    }

    /**
     * The remembered normal force @p N_m (N; negative: none) of a wall
     * node that pushes on its wall, after a step: the present force
     * @p now at first contact (none remembered, or the wall did not hold
     * the node in the last step: @p held false), else relax()ed towards
     * it. Returns the new N_m. (A node that does not push forgets: N_m =
     * -1, the caller's.)
     */
    double
    remember(double      &N_m,
             const bool   held,
             const double now,
             const double slip_speed,
             const double dt) const
    {
      N_m = held && N_m >= 0 ? relax(N_m, now, slip_speed, dt) : now;
      return N_m;
    }

    double length = 0;
    double speed  = 0.1;
  };
} // namespace MPM

#endif
