#include <mpm/boundary_conditions/boundary_conditions.h>
#include <mpm/grid/nodal_vector.h>
#include <mpm/transfer/particle_grid_weights.h>
#include <mpm/transfer/transfer_scheme.h>

#include <vector>

namespace MPM
{
  /**
   * 'Transfer/Scheme = xpic': XPIC(m) (Hammerquist and Nairn 2017): PIC
   * from a grid velocity in which the smoothing of the particle-grid-
   * particle round trip is undone to order m. The brought grid velocity u
   * becomes u* = sum_{k=1}^m c_k (P S S+)^{k-1} u with
   * c_k = (-1)^{k+1} binomial(m, k), S+ the interpolation to the points,
   * S their mass-weighted projection back
   * (ParticleGridWeights::round_trip()) and P the wall constraints. On the
   * points this is 1 - (1 - A)^m with A = S+ S, whose eigenvalues lie in
   * [0, 1]: the filter's lie in [0, 1] too (no mode is amplified), those
   * of the smooth modes (A near 1) move much closer to 1 than PIC's A,
   * and the null modes (noise) stay at 0. The filtered nodal velocity can
   * overshoot at light nodes (a material's edge): doc/transfers.md. Each
   * order beyond 1 costs one pass over the points that reads only their
   * masses and weights.
   */
  template <int dim>
  class Xpic : public TransferScheme<dim>
  {
  public:
    explicit Xpic(ParameterHandler &prm)
      : order(prm.get_integer("XPIC order"))
    {
      double binomial = 1;
      for (unsigned int k = 1; k <= order; ++k)
        {
          binomial = binomial * (order - k + 1) / k;
          coefficients.push_back((k % 2 == 1 ? 1. : -1.) * binomial);
        }
    }

    void
    add_nodal_fields(NodalFields &nodal) override
    {
      nodal.add(filtered_velocity, NodalFields::Ghosts::computed);
      nodal.add(round_trip_velocity, NodalFields::Ghosts::computed);
      nodal.add(round_trip_momentum, NodalFields::Ghosts::summed);
    }

    bool
    filters_brought_velocity() const override
    {
      return order > 1;
    }

    void
    filter_brought_velocity(ParticleGridWeights<dim>       &weights,
                            const BoundaryConditions<dim> &boundary_conditions,
                            NodalFields                   &nodal) override
    {
      const auto &active_dofs = weights.active_dofs();
      // u_1 = the constrained brought velocity
      // (Simulator::compute_nodal_velocity()).
      for (const unsigned int i : active_dofs)
        {
          const double u                       = nodal.velocity.local_element(i);
          round_trip_velocity.local_element(i) = u;
          filtered_velocity.local_element(i)   = coefficients[0] * u;
        }
      for (unsigned int k = 1; k < coefficients.size(); ++k)
        {
          // u_{k+1} = P S S+ u_k: interpolate to the points, project back
          // with their masses, constrain.
          weights.round_trip(round_trip_velocity, round_trip_momentum);
          for (const unsigned int i : active_dofs)
            {
              const double m = nodal.mass.local_element(i);
              round_trip_velocity.local_element(i) =
                m > 0 ? round_trip_momentum.local_element(i) / m : 0.;
            }
          // The same projection as u_1's.
          boundary_conditions.project_velocity(
            round_trip_velocity,
            BoundaryConditions<dim>::Contact::as_last_update);
          for (const unsigned int i : active_dofs)
            filtered_velocity.local_element(i) +=
              coefficients[k] * round_trip_velocity.local_element(i);
        }
      // The nodal update starts from the brought velocity p / m: it is now
      // the filtered one, so friction and the walls act on it.
      for (const unsigned int i : active_dofs)
        nodal.momentum.local_element(i) =
          nodal.mass.local_element(i) * filtered_velocity.local_element(i);
    }

  private:
    unsigned int        order;
    std::vector<double> coefficients;
    /// The filtered velocity, the round trip's iterate and its sums.
    NodalVector filtered_velocity;
    NodalVector round_trip_velocity;
    NodalVector round_trip_momentum;
  };
} // namespace MPM

MPM_REGISTER_TRANSFER_SCHEME(MPM::Xpic,
                             "xpic",
                             "XPIC(m) (Hammerquist and Nairn 2017): PIC from a "
                             "grid velocity in which the round trip's "
                             "smoothing is undone to order m ('XPIC order').")
