#ifndef mpm_boundary_conditions_wall_gap_h
#define mpm_boundary_conditions_wall_gap_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/boundary_conditions/wall_constraints.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/nodal_vector.h>

#include <functional>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Whether the material touches a frictional wall at each of its nodes:
   * the gap between the material and the wall, measured from the points.
   *
   * A frictional wall node is unilateral: it holds the material's normal
   * velocity only while the node moves into the wall. That rule is about
   * the node's velocity, not about where the material is. A node moving
   * away is free, so material near it can leave the wall (a block rocking
   * as friction decelerates it); once it has left, a node moving into the
   * wall is held again, and the material can never come back down within
   * the first cell. Step by step the rocking ratchets the material up off
   * the bed (measured: a block decelerated by friction rode 5 cm above a
   * flat bed on 0.25 m cells, and more the finer the mesh).
   *
   * Here the contact also asks the material (Nairn's displacement check,
   * for a rigid wall): for each point in a cell with a face on a
   * frictional wall, the gap between the point's domain and the face's
   * plane, (x_f - x_p) . n_f - r_p with r_p how far the point's domain
   * reaches towards the wall (Reach: ParticleGridWeights::reach_along());
   * the point touches the wall if that gap is at most 'Contact gap
   * tolerance' times r_p. A wall node is in contact
   * (held as before) if one of the points in the wall cells around it
   * touches, or if no point lies in those cells (material reaching the
   * node from farther, as CPDI domains do: the rule of the node's velocity
   * alone). Otherwise the material around the node has left the wall: the
   * node is free both ways, and the material falls back onto the wall.
   */
  template <int dim>
  class WallGap
  {
  public:
    /// How far a point's material reaches from it along a unit vector
    /// (ParticleGridWeights::reach_along()), given its properties.
    using Reach = std::function<double(const double *, const Tensor<1, dim> &)>;

    /// 'Boundary conditions/Wall contact' and 'Contact gap tolerance'.
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Find the wall cells (locally owned cells with a face on a frictional
     * boundary of @p specs) and their faces' planes, and which of @p nodes
     * (whose local elements number @p layout) their vertices are.
     */
    void
    setup(const BackgroundGrid<dim>               &grid,
          const std::vector<BoundarySpec<dim>>    &specs,
          const NodalVector                       &layout,
          const std::vector<ConstrainedNode<dim>> &nodes);

    /**
     * Measure the gaps of the points of this step (located in their
     * cells); collective.
     */
    void
    update(const Particles::ParticleHandler<dim> &particles,
           const Reach                           &reach);

    /// Whether update() measures anything ('Wall contact = gap' and a
    /// frictional wall in the mesh on some rank).
    bool
    measures() const
    {
      return active;
    }

    /// Whether the material touches the wall at node @p k (index into the
    /// nodes of setup()).
    bool
    touches(const unsigned int k) const
    {
      return k >= in_contact.size() || in_contact[k];
    }

  private:
    /// A frictional node: its index among the nodes of setup() and the
    /// entries of counts that hold its points near and touching.
    struct WallNode
    {
      unsigned int k;
      unsigned int near_dof;
      unsigned int touching_dof;
    };
    /// A locally owned cell's face on a frictional wall: its plane and
    /// its vertices' WallNodes.
    struct WallFace
    {
      typename Triangulation<dim>::active_cell_iterator cell;
      Point<dim>                                        centre;
      Tensor<1, dim>                                    normal;
      std::vector<unsigned int>                         wall_nodes;
    };
    std::vector<WallNode> wall_nodes;
    std::vector<WallFace> faces;
    /// Per node (two components of its nodal entries): the points near
    /// it, the points touching.
    NodalVector                counts;
    std::vector<unsigned char> in_contact;
    bool                       by_gap    = false;
    bool                       active    = false;
    double                     tolerance = 0.1;
  };
} // namespace MPM

#endif
