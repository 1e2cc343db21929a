#include <mpm/transfer/transfer_scheme.h>

#include <cmath>

namespace MPM
{
  /**
   * 'Transfer/Scheme = flip/pic blend': v_p <- theta (v_p + dt S+ a) +
   * (1 - theta) S+ v_L. theta = 0 is PIC (dissipative: every step keeps
   * only the part of the point velocities that the grid represents, and
   * smooths that), theta = 1 is FLIP (no filtering: noisy).
   *
   * Each step the blend keeps the share theta of the part of the point
   * velocities that the grid does not represent and replaces the rest by
   * the grid's (PIC's damping). With one theta per step that damping per
   * unit time grows as the time step shrinks: halving the CFL number at
   * theta = 0.98 damps like theta = 0.96 at the original step, and moved
   * the flume's final front by 1.2 cm (doc/transfers.md). With 'FLIP
   * fraction time step' dt_ref > 0, theta is the share kept per dt_ref and
   * a step keeps theta^(dt / dt_ref): the same damping per unit time at
   * every time step (the flume at CFL 0.25 then matches CFL 0.5 within
   * 2 mm).
   */
  template <int dim>
  class FlipPicBlend : public TransferScheme<dim>
  {
  public:
    explicit FlipPicBlend(ParameterHandler &prm)
      : flip(prm.get_double("FLIP fraction"))
      , flip_time_step(prm.get_double("FLIP fraction time step"))
    {}

    double
    flip_fraction(const double dt) const override
    {
      if (flip_time_step > 0 && flip > 0 && flip < 1)
        return std::pow(flip, dt / flip_time_step);
      return flip;
    }

  private:
    double flip;
    /// The time step 'FLIP fraction' refers to (0: every step).
    double flip_time_step;
  };
} // namespace MPM

MPM_REGISTER_TRANSFER_SCHEME(MPM::FlipPicBlend,
                             "flip/pic blend",
                             "v_p <- theta (v_p + dt S+ a) + (1 - theta) S+ v "
                             "with theta = 'FLIP fraction' (0 = PIC, "
                             "1 = FLIP).")
