#ifndef mpm_grid_inverse_mapping_h
#define mpm_grid_inverse_mapping_h

#include <deal.II/base/geometry_info.h>
#include <deal.II/base/point.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/grid/tria.h>

#include <array>
#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * How the reference coordinates of a point in a bilinear (isoparametric)
   * cell are computed. All three give the same answer to round-off wherever
   * they all succeed (see tests/unit/inverse_mapping.cc); they differ in cost
   * and in how they fail:
   *
   * - closed_form: the explicit inverse of the 2D bilinear map (Zhao et al.
   *   1999, Eq. 1-3 of the paper, rewritten for deal.II's reference cell),
   *   i.e. one quadratic equation, plus one Newton step as polish. No
   *   iteration, no exceptions. In 3D the explicit inverse where the
   *   hexahedron has one (an extruded cell, as in terrain-following
   *   meshes: ExtrudedCellMap) and Newton's iteration elsewhere.
   * - newton: Newton's method on the multilinear map, started from the
   *   affine approximation at the cell centre, as deal.II's MappingQ1 does
   *   as its fall-back. Any dim.
   * - dealii: deal.II's own MappingQ1::transform_real_to_unit_cell(), which
   *   throws on failure; the exception is caught and turned into a failed
   *   result. Needs a cell iterator and a Mapping. Kept for comparison.
   */
  enum class InverseMappingType
  {
    closed_form,
    newton,
    dealii
  };

  /**
   * The names accepted by parse_inverse_mapping_type(), as a
   * Patterns::Selection string: "closed form|newton|deal.II".
   */
  std::string
  inverse_mapping_type_selection();

  /**
   * Map a parameter value ("closed form", "newton" or "deal.II") to the
   * enum. Throws InputError for anything else.
   */
  InverseMappingType
  parse_inverse_mapping_type(const std::string &name);

  /**
   * The inverse of parse_inverse_mapping_type().
   */
  std::string
  to_string(const InverseMappingType type);

  /**
   * Result of an inverse mapping. The functions in this file report
   * failure through @p success instead of throwing, because in a point
   * location loop "this point is not in (the extension of) this cell" is
   * the common case, not an error. When @p success is false, @p xi is
   * meaningless (it may be NaN).
   */
  template <int dim>
  struct InverseMappingResult
  {
    Point<dim>   xi;
    bool         success      = false;
    unsigned int n_iterations = 0;
  };

  /**
   * Tolerance, in reference coordinates, of inside_unit_cell(). It is
   * larger than the round-off of the inverse mapping of a point on an edge
   * (a few 1e-16 for well-shaped cells, up to about 1e-13 for rotated cells
   * of aspect ratio 1000), so that a point on an edge or vertex belongs to
   * every cell that shares it, and much smaller than anything physical: a
   * point 1e-12 of a cell width outside a cell is, for the MPM, on its edge.
   */
  constexpr double reference_cell_tolerance = 1e-12;

  /**
   * Whether the reference point @p xi lies in the closed unit cell
   * [0,1]^dim enlarged by @p tolerance on each side. Points on an edge or a
   * vertex are inside. NaN coordinates (a failed inverse mapping) are
   * outside. There is no clamping: a point 1e-8 outside is outside.
   *
   * A point on an edge shared by several cells is inside all of them; which
   * one owns it is decided by locate_point() (lowest active cell index).
   */
  template <int dim>
  inline bool
  inside_unit_cell(const Point<dim> &xi,
                   const double      tolerance = reference_cell_tolerance)
  {
    for (unsigned int d = 0; d < dim; ++d)
      if (!(xi[d] >= -tolerance && xi[d] <= 1. + tolerance))
        return false;
    return true;
  }

  /**
   * The real point x(xi) = sum_i N_i(xi) v_i of the multilinear map of a
   * cell with @p vertices (deal.II order) at reference point @p xi.
   */
  template <int dim>
  Point<dim>
  map_unit_to_real(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                     &vertices,
    const Point<dim> &xi);

  /**
   * Closed-form inverse of the bilinear map of the quadrilateral with
   * @p vertices (deal.II's lexicographic order: v0 = x(0,0), v1 = x(1,0),
   * v2 = x(0,1), v3 = x(1,1)). Writing x(xi, eta) = a + b xi + c eta +
   * d xi eta, eliminating one coordinate gives a quadratic in the other;
   * doc/point_location.md has the equations. The quadratic is solved with
   * the cancellation-free formula, the coordinate whose quadratic is closer
   * to linear is the one solved for, the parallelogram (d = 0) and any
   * vanishing leading coefficient fall out of the same formula without a
   * division by zero, and of the (up to) two roots the one whose reference
   * point is inside or nearest to the unit square is returned.
   *
   * If @p newton_polish is true (the default), one Newton step on the
   * bilinear map follows where the root is ill-conditioned (the square root
   * of the discriminant, the Jacobian determinant at the point up to the
   * cell's scale, below a quarter of |A| + |B|: near a corner of a nearly
   * degenerate cell); it removes the error that the conditioning amplifies
   * there, at the cost of one evaluation of the map and its Jacobian.
   * Elsewhere the root is accurate to a few eps and the step is skipped.
   *
   * Fails (success = false) only if the quadratic has no real root, i.e.
   * the point is outside the region the bilinear map of the plane covers
   * (always far outside the cell), or the cell is degenerate.
   */
  InverseMappingResult<2>
  inverse_map_closed_form(const std::array<Point<2>, 4> &vertices,
                          const Point<2>                &x,
                          const bool                     newton_polish = true);

  /**
   * The 3D counterpart: the closed-form inverse of a hexahedron extruded
   * along one reference direction (its edges along it parallel to one
   * coordinate axis: terrain-following cells), Newton's iteration
   * (inverse_map_newton()) for any other (ExtrudedCellMap).
   */
  InverseMappingResult<3>
  inverse_map_closed_form(const std::array<Point<3>, 8> &vertices,
                          const Point<3>                &x);

  /**
   * Newton's method for the inverse of the multilinear map of a cell with
   * @p vertices (deal.II order), started from the affine map that agrees
   * with the cell's map and Jacobian at the cell centre. A step is halved
   * (up to 10 times) while it increases the residual, as in deal.II.
   * Converged when a step is at most @p step_tolerance in every reference
   * coordinate; because convergence is quadratic, the error after that step
   * is of the order of step_tolerance^2, i.e. round-off. A tolerance on the
   * step rather than on the real-space residual is used because the latter
   * has a floor of eps |x| that depends on where the cell is.
   *
   * Fails (success = false, no exception) if @p max_iterations steps do not
   * converge or the Jacobian is singular at an iterate.
   */
  template <int dim>
  InverseMappingResult<dim>
  inverse_map_newton(
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                      &vertices,
    const Point<dim>  &x,
    const double       step_tolerance = 1e-10,
    const unsigned int max_iterations = 20);

  /**
   * deal.II's Mapping::transform_real_to_unit_cell() with the exception it
   * throws when it fails caught and reported as success = false.
   */
  template <int dim>
  InverseMappingResult<dim>
  inverse_map_dealii(const Mapping<dim>                               &mapping,
                     const typename Triangulation<dim>::cell_iterator &cell,
                     const Point<dim>                                 &x);

  /**
   * The inverse mapping selected in the parameter file, bound to the
   * mapping of the background grid. This is what the MPM step calls per
   * point: transform_real_to_unit_cell(cell, x).
   */
  template <int dim>
  class InverseMapping
  {
  public:
    /**
     * @p mapping must be a MappingQ1 (or another mapping that is the
     * multilinear map of the vertices); it is only used by
     * InverseMappingType::dealii but must outlive this object.
     */
    InverseMapping(const InverseMappingType type, const Mapping<dim> &mapping);

    InverseMappingType
    type() const
    {
      return mapping_type;
    }

    /**
     * Reference coordinates of @p x in @p cell, by the selected method.
     * Does not check whether the result is inside the cell; use
     * inside_unit_cell() for that.
     */
    InverseMappingResult<dim>
    transform_real_to_unit_cell(
      const typename Triangulation<dim>::cell_iterator &cell,
      const Point<dim>                                 &x) const;

    /**
     * The same for a cell given by its vertices (deal.II order); not
     * available for InverseMappingType::dealii, which needs a cell.
     */
    InverseMappingResult<dim>
    transform_real_to_unit_cell(
      const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>
                       &vertices,
      const Point<dim> &x) const;

  private:
    InverseMappingType  mapping_type;
    const Mapping<dim> *mapping;
  };
} // namespace MPM

#endif
