#ifndef mpm_boundary_conditions_wall_constraints_h
#define mpm_boundary_conditions_wall_constraints_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/affine_constraints.h>

#include <mpm/boundary_conditions/node_frames.h>
#include <mpm/grid/nodal_vector.h>

#include <array>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * A node that carries a constraint, in the numbering of the local
   * elements of a ghosted vector, with what the nodal update applies to
   * it: the orthogonal projector in its frame and, on a frictional wall,
   * the wall's basal law.
   */
  template <int dim>
  struct ConstrainedNode
  {
    /// Local element index of each velocity component.
    std::array<unsigned int, dim> local_dofs;
    /// Orthogonal projector onto the admissible velocities.
    Tensor<2, dim> projector;
    /// Particular solution of the inhomogeneous constraints.
    Tensor<1, dim> offset;
    /// Unilateral contact and a basal law at this node (a node with one
    /// wall normal, of a frictional boundary)?
    bool frictional = false;
    /// Unit outward normal of the node's frame.
    Tensor<1, dim> normal;
    /// The basal law of a frictional node, and its wall geometry.
    const BasalLaw<dim> *law = nullptr;
    WallNodeGeometry     geometry;
    /// A 3D edge node (two wall normals, one free direction) of which at
    /// least one wall is frictional: the two normals (unit) and the law of
    /// each (nullptr for a slip wall). The laws act on the velocity along
    /// the edge with the walls' reactions
    /// (WallFriction::edge_frictional_acceleration()); the contact is
    /// bilateral.
    bool                                 edge_friction = false;
    std::array<Tensor<1, dim>, 2>        edge_normals;
    std::array<const BasalLaw<dim> *, 2> edge_laws{};
    std::array<WallNodeGeometry, 2>      edge_geometry;
    /// The mesh vertex of the node.
    Point<dim> location;
  };


  /**
   * The wall constraints of the node frames @p frames as AffineConstraints
   * lines (rows n . v = b, as VectorTools::compute_no_normal_flux_constraints
   * makes them): Gauss-Jordan elimination with column pivoting expresses
   * the pivot components through the free ones. @p constraints is
   * reinitialised for the locally relevant dofs @p relevant and closed.
   */
  template <int dim>
  void
  make_wall_constraints(const std::vector<NodeFrame<dim>> &frames,
                        const IndexSet                    &relevant,
                        AffineConstraints<double>         &constraints);

  /**
   * Each constrained node's orthogonal projector, read back from the
   * AffineConstraints lines: a line v_p = sum_c a_c v_c + b is the row
   * (e_p - sum_c a_c e_c) . v = b, and v <- P v + q with
   * P = I - R^T (R R^T)^{-1} R. This is what condensing the lumped-mass
   * system does; AffineConstraints::distribute() would instead overwrite
   * the pivot component, an oblique projection that changes the
   * tangential velocity on a tilted wall.
   */
  template <int dim>
  std::vector<ConstrainedNode<dim>>
  make_projections(const std::vector<NodeFrame<dim>> &frames,
                   const AffineConstraints<double>   &constraints,
                   const NodalVector                 &layout);
} // namespace MPM

#endif
