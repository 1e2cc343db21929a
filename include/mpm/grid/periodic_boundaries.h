#ifndef mpm_grid_periodic_boundaries_h
#define mpm_grid_periodic_boundaries_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>

#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Pairs of mesh boundaries that are one ('Mesh/Periodic boundaries'): a
   * layer of material that repeats itself along a direction, such as a
   * sample in simple shear or an infinite slope, is modelled by one period
   * of it. Two things make a boundary pair periodic in the MPM:
   *  - the nodes on the two boundaries are one node: what the points
   *    bring to either is summed and both carry the sum (PeriodicNodeGroups,
   *    after every particle-to-grid sum), so that the two nodes have the
   *    same velocity;
   *  - a material point that leaves through one boundary enters through
   *    the other: wrap() moves it by the period.
   *
   * Each boundary of a pair must be a plane normal to one coordinate
   * direction of the parameter file's frame (x = const, ...; the scene
   * rotation, 'Mesh/Scene rotation angle', turns the pair with the mesh,
   * so an infinite slope is a rectangle in the slope's own frame), and the
   * faces of the two must match one to one after a translation along that
   * direction (GridTools::collect_periodic_faces()). The pairs are given
   * to the p4est forest (add_periodicity()), so that the cells across a
   * periodic boundary are ghost cells on every rank and a point that wraps
   * to another rank is sent there like any point that crosses a partition
   * boundary.
   */
  template <int dim>
  class PeriodicBoundaries
  {
  public:
    /// The entry 'Periodic boundaries' of the subsection 'Mesh'.
    static void
    declare_parameters(ParameterHandler &prm);

    /// Read it (inside the subsection 'Mesh').
    void
    parse_parameters(ParameterHandler &prm);

    /// Whether any pair was given.
    bool
    empty() const
    {
      return pairs.empty();
    }

    /**
     * Check the pairs on the coarse mesh @p triangulation (before any
     * refinement and before the scene rotation: the planes are those of
     * the parameter file's frame) and make them periodic in the forest.
     * An InputError names the pair that is not periodic.
     */
    void
    apply_to_coarse_mesh(
      parallel::distributed::Triangulation<dim> &triangulation);

    /**
     * The scene rotation @p rotation (mesh frame = rotation x scene
     * frame): the planes and the periods in the mesh's frame.
     */
    void
    set_rotation(const Tensor<2, dim> &rotation);

    /**
     * If @p x (mesh frame) lies beyond a periodic plane, move it by the
     * period back into the layer and return the translation; otherwise
     * return zero and leave @p x.
     */
    Tensor<1, dim>
    wrap(Point<dim> &x) const
    {
      Tensor<1, dim> shift;
      for (const auto &pair : pairs)
        {
          const double s = pair.normal * x;
          if (s > pair.upper)
            shift -= pair.period;
          else if (s < pair.lower)
            shift += pair.period;
        }
      x += shift;
      return shift;
    }

    /**
     * The groups of degrees of freedom of @p dof_handler that the pairs
     * make one node (two per node of a pair's boundary, four at a node
     * where two pairs meet, ...), as global indices in ascending order,
     * for the groups with a member in @p locally_relevant_dofs. Call after
     * every distribution of the degrees of freedom.
     */
    std::vector<std::vector<types::global_dof_index>>
    node_groups(const DoFHandler<dim> &dof_handler,
                const IndexSet        &locally_relevant_dofs) const;

    /// The boundary ids of all pairs (they need no boundary condition).
    std::vector<types::boundary_id>
    boundary_ids() const;

  private:
    struct Pair
    {
      types::boundary_id first  = 0;
      types::boundary_id second = 0;
      /// The coordinate direction (parameter file's frame).
      unsigned int       direction = 0;
      /// The planes' coordinates along the direction, lower < upper:
      /// in the scene frame x_d, in the mesh frame normal . x (the same
      /// number, normal = R e_d), so one pair serves both.
      double             lower = 0, upper = 0;
      /// Mesh frame: the unit normal of the planes and the period
      /// (upper - lower) normal.
      Tensor<1, dim>     normal;
      Tensor<1, dim>     period;
    };
    std::vector<Pair> pairs;
  };
} // namespace MPM

#endif
