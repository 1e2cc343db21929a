#ifndef mpm_boundary_conditions_wall_friction_h
#define mpm_boundary_conditions_wall_friction_h

#include <deal.II/base/tensor.h>

#include <mpm/boundary_conditions/basal_law.h>

#include <array>
#include <optional>

namespace MPM
{
  using namespace dealii;

  /**
   * A frictional wall's tangential resistance at one node, in the node's
   * own frame: the normal reaction that keeps the node on its wall, and
   * the node's basal law (BasalLaw) acting on the tangential motion. The
   * normal component is left for the wall projection
   * (BoundaryConditions::project_velocity()).
   */
  namespace WallFriction
  {
    /**
     * The acceleration of a node with one wall normal after the wall's
     * resistance, for velocity @p v and acceleration @p a (global frame),
     * outward unit normal @p n, basal law @p law with the node's
     * @p geometry, over a step @p dt. With the normal reaction per unit
     * mass r = v.n/dt + a.n (resistance only if r > 0: the wall only
     * pushes) and the trial tangential velocity v_t* = v_t + dt a_t, the
     * node sticks (v_t' = 0) if |v_t*| <= mu r dt, else v_t' = v_t* (1 -
     * mu r dt / |v_t*|), then reduced by the law's rate-dependent part
     * (BasalLaw::sliding_speed()). This is the static rule at rest (stick
     * while |a_t| <= mu r), the kinetic rule when sliding (a_t reduced by
     * mu r, stopping rather than reversing), and the resistance never
     * reverses the motion. @p sticks tells whether the node stuck.
     *
     * The rate-dependent part also acts where r <= 0 if the last nodal
     * update held the node on its wall (@p held): a node at the edge of a
     * body resting on the wall sees a reaction that flickers about zero
     * from step to step (the internal forces of its partly filled cells),
     * and Voellmy's drag, which does not depend on the normal stress, would
     * be lost at every flicker (measured: 2.5 % of a sliding block's drag
     * impulse). Coulomb's part is not affected: the normal impulse a
     * flicker misses is taken up by the next steps' reactions.
     *
     * The rate-independent resistance takes r itself unless the caller
     * gives the normal reaction per unit mass it takes instead,
     * @p effective_reaction (BoundaryConditions::apply_friction(): with
     * pore water r less what the water carries, with a normal-stress
     * memory the remembered normal force over the node's mass); it acts
     * only where r > 0.
     */
    template <int dim>
    Tensor<1, dim>
    frictional_acceleration(
      const Tensor<1, dim>        &v,
      const Tensor<1, dim>        &a,
      const Tensor<1, dim>        &n,
      const BasalLaw<dim>         &law,
      const WallNodeGeometry      &geometry,
      const double                 dt,
      bool *const                  sticks             = nullptr,
      const bool                   held               = false,
      const std::optional<double> &effective_reaction = std::nullopt);

    /**
     * The normal reaction per unit mass r = v.n / dt + a.n that a wall of
     * outward normal @p n must give a node of velocity @p v and
     * acceleration @p a for its normal velocity to be zero after the step
     * @p dt.
     */
    template <int dim>
    inline double
    normal_reaction(const Tensor<1, dim> &v,
                    const Tensor<1, dim> &a,
                    const Tensor<1, dim> &n,
                    const double          dt)
    {
      return (v * n) / dt + a * n;
    }

    /**
     * The same at a 3D edge node (two walls, one free direction): the
     * trial velocity w = v + dt a is brought onto the edge by wall
     * impulses lambda_j n_j (the Gram system of the two outward normals
     * @p n); wall j pushes if lambda_j < 0. The rate-independent capacity
     * is sum_j mu_j max(0, -lambda_j) over the walls with a law
     * (@p laws[j] nullptr for a slip wall), and the rate-dependent parts
     * of the pushing walls act on the remaining speed along the edge.
     * With pore water, @p relief[j] (per unit mass and time, as in
     * frictional_acceleration()) is what wall j's push holds beyond the
     * effective normal force: its impulse counts as
     * max(0, -lambda_j - dt relief_j), unless the caller gives the
     * impulses the walls' Coulomb parts take instead,
     * @p effective_impulses (BoundaryConditions::apply_friction(): a
     * normal-stress memory).
     */
    template <int dim>
    Tensor<1, dim>
    edge_frictional_acceleration(
      const Tensor<1, dim>                       &v,
      const Tensor<1, dim>                       &a,
      const std::array<Tensor<1, dim>, 2>        &n,
      const std::array<const BasalLaw<dim> *, 2> &laws,
      const std::array<WallNodeGeometry, 2>      &geometry,
      const double                                dt,
      bool *const                                 sticks = nullptr,
      const std::array<double, 2>                &relief = {{0., 0.}},
      const std::array<double, 2>                *effective_impulses = nullptr);

    /**
     * The normal impulses per unit mass -lambda_j of
     * edge_frictional_acceleration(), positive where wall j pushes, that
     * bring the trial velocity v + dt a of a node onto the edge of the
     * walls of outward unit normals @p n; nullopt where the normals are
     * parallel (no edge).
     */
    template <int dim>
    inline std::optional<std::array<double, 2>>
    edge_wall_impulses(const Tensor<1, dim>                &v,
                       const Tensor<1, dim>                &a,
                       const std::array<Tensor<1, dim>, 2> &n,
                       const double                         dt)
    {
      const Tensor<1, dim> w   = v + dt * a;
      const double         g01 = n[0] * n[1];
      const double         det = 1 - g01 * g01;
      if (det <= 0)
        return std::nullopt;
      const double r0 = -(n[0] * w), r1 = -(n[1] * w);
      return std::array<double, 2>{
        {-(r0 - g01 * r1) / det, -(r1 - g01 * r0) / det}};
    }

    /**
     * The part of @p u along the edge of the walls of outward unit
     * normals @p n (the edge's free direction), for a Gram determinant
     * @p det = 1 - (n_0.n_1)^2 > 0.
     */
    template <int dim>
    inline Tensor<1, dim>
    along_edge(const Tensor<1, dim>                &u,
               const std::array<Tensor<1, dim>, 2> &n,
               const double                         det)
    {
      const double g01 = n[0] * n[1];
      return u + ((n[0] * u) * (g01 * n[1] - n[0]) +
                  (n[1] * u) * (g01 * n[0] - n[1])) /
                   det;
    }
  } // namespace WallFriction
} // namespace MPM

#endif
