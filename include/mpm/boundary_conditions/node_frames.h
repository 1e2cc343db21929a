#ifndef mpm_boundary_conditions_node_frames_h
#define mpm_boundary_conditions_node_frames_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <mpm/boundary_conditions/boundary_spec.h>
#include <mpm/grid/background_grid.h>
#include <mpm/grid/periodic_node_groups.h>
#include <mpm/grid/nodal_vector.h>

#include <array>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The frame of one boundary node: the wall normals it is constrained
   * along (rows n . v = b) and, for a frictional node, its wall's basal law.
   */
  template <int dim>
  struct NodeFrame
  {
    std::array<types::global_dof_index, dim> dofs;
    Point<dim>                               location;
    /// Unit constraint normals and their right-hand sides.
    std::vector<Tensor<1, dim>> normals;
    std::vector<double>         values;
    /// One (possibly merged) wall normal of a frictional boundary:
    /// unilateral contact with @p law.
    bool                 frictional = false;
    const BasalLaw<dim> *law        = nullptr;
    WallNodeGeometry     geometry;
    /// A 3D edge node (two wall normals) of which at least one wall is
    /// frictional: the unit normals, each wall's law (nullptr for slip).
    bool                                 edge_friction = false;
    std::array<Tensor<1, dim>, 2>        edge_normals;
    std::array<const BasalLaw<dim> *, 2> edge_laws{};
    std::array<WallNodeGeometry, 2>      edge_geometry;
  };


  /**
   * The frames of every locally relevant boundary node of @p specs'
   * boundaries, in the numbering of @p layout (a ghosted nodal vector):
   *
   * 1. each boundary's outward normal at a node is the face-size weighted
   *    average of the outward normals of the node's faces with the
   *    boundary's ids (summed over ranks, so that nodes on partition
   *    boundaries agree), or the given normal;
   * 2. the corner rule of BoundaryConditions: a fixed boundary wins, then
   *    a prescribed velocity; otherwise the normals of all slip and
   *    friction boundaries are constrained, normals within 10 degrees of
   *    each other merged into their average (with the basal law of
   *    largest friction coefficient among the merged frictional
   *    boundaries); dim different normals fix the node.
   *
   * Where a basal law is rate-dependent, its nodes' WallNodeGeometry
   * (A_i / V_i and |g| = @p gravity) is computed too.
   *
   * With periodic boundaries (@p periodic_nodes), the face sums (normals,
   * wall areas, volumes) of a node's periodic copies are added together,
   * so that the copies get the same frame.
   */
  template <int dim>
  std::vector<NodeFrame<dim>>
  compute_node_frames(const BackgroundGrid<dim>             &grid,
                      const NodalVector                     &layout,
                      const std::vector<BoundarySpec<dim>>  &specs,
                      const double                           gravity,
                      const PeriodicNodeGroups              *periodic_nodes);
} // namespace MPM

#endif
