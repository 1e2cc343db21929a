#ifndef mpm_material_points_nonlocal_averaging_h
#define mpm_material_points_nonlocal_averaging_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/particles/particle_handler.h>

#include <mpm/materials/material_library.h>

#include <array>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The non-local average of one variable of the material points,
   *
   *   v_avg(x) = sum_p w(|x - x_p|) V_p v_p / sum_p w(|x - x_p|) V_p,
   *   w(r) = (1 - r^2 / R^2)^2 for r < R, else 0
   *
   * (the truncated quartic "bell" of Bazant and Jirasek 2002; V_p the
   * points' volumes), evaluated on a uniform auxiliary grid of spacing
   * R / nodes_per_radius: the numerator and the denominator are summed
   * exactly at the grid's nodes and interpolated (multilinearly) to the
   * points. Why a grid: a sum over the pairs of points within R costs
   * (R / h)^dim per point for cells of size h, so refining the mesh at a
   * fixed radius (what a convergence study of a regularised softening
   * does) would make the averaging the whole cost of a fine run; through
   * the grid each point costs about (2 nodes_per_radius)^dim kernel
   * values, whatever the mesh. The grid depends on R alone (its origin is
   * a multiple of its spacing), never on the background mesh, so the
   * operator it defines is the same on every mesh: the kernel is w
   * interpolated between nodes (within 3 % of w's peak for 4 nodes per
   * radius) and a constant field is averaged to itself exactly.
   *
   * On several MPI ranks the grid covers the material's points of all
   * ranks and its sums are added over the ranks (then the averages differ
   * from one rank's by round-off, the order of the sums). On several
   * threads add_points() gives each thread a slab of node rows; the sums
   * are the same on any number of threads.
   */
  template <int dim>
  class NonlocalGrid
  {
  public:
    /// Grid nodes per radius R (the spacing is R / nodes_per_radius).
    static constexpr unsigned int nodes_per_radius = 4;

    /**
     * A grid for radius @p radius covering the points within the box
     * [@p lower, @p upper] (all ranks' points), zeroed. @p material_name
     * is named in the error thrown when the grid would be too large (more
     * than 1e8 nodes).
     */
    void
    reinit(const Point<dim>  &lower,
           const Point<dim>  &upper,
           const double       radius,
           const std::string &material_name);

    /// Add a point at @p x with volume @p volume and value @p value.
    void
    add(const Point<dim> &x, const double volume, const double value);

    /**
     * Add the points @p x with volumes @p volume and values @p value, on
     * the threads of this rank: each thread adds a slab of node rows (along
     * the last direction) from the points near it. Every node receives its
     * contributions in one order, that of the points' rows and then of
     * their indices, whatever the number of threads, so the sums are the
     * same bit for bit on any number (and differ from adding the points
     * one by one with add() in their index order by round-off).
     */
    void
    add_points(const std::vector<Point<dim>> &x,
               const std::vector<double>     &volume,
               const std::vector<double>     &value);

    /// Sum the grid's values over the ranks of @p comm (nothing on one).
    void
    sum_over(const MPI_Comm comm);

    /// The average at @p x, which must be a point that was added (or lie
    /// within R / nodes_per_radius of one, so that the weights are not
    /// all zero).
    double
    average(const Point<dim> &x) const;

    /// Nodes of the grid.
    std::size_t
    n_nodes() const
    {
      return sums.size();
    }

  private:
    /// add() restricted to the node rows [@p row_begin, @p row_end) of the
    /// last direction.
    void
    add_rows(const Point<dim>  &x,
             const double       volume,
             const double       value,
             const unsigned int row_begin,
             const unsigned int row_end);

    /// The row of nodes (last direction) at or below @p x.
    unsigned int
    row_of(const Point<dim> &x) const;

    double                      radius  = 0;
    double                      spacing = 0;
    Point<dim>                  origin;
    std::array<unsigned int, dim> n_nodes_per_direction{};
    /// Per node: sum of w V v and of w V.
    std::vector<std::array<double, 2>> sums;
    /// add_points(): the first index into order of each row's points, and
    /// the points sorted by row.
    std::vector<unsigned int> row_start, order;
    /// add_points(): the first row of each slab of rows that one thread
    /// adds, and the end.
    std::vector<unsigned int> slab_start;
  };


  /**
   * The regularised state variables of the materials whose model asks for
   * one (MaterialModel::nonlocal_variable()): before every stress update
   * the MPM step calls update(), which writes into each point of such a
   * material max(0, (1 - m) v + m v_avg) (NonlocalGrid for v_avg). Materials
   * without a non-local variable cost nothing; a material whose variable
   * is still zero everywhere (nothing has yielded) costs one pass over
   * its points.
   */
  template <int dim>
  class NonlocalAveraging
  {
  public:
    explicit NonlocalAveraging(const MaterialLibrary &materials);

    /// Whether some material has a non-local variable.
    bool
    active() const;

    /**
     * Write the regularised variable of every point of @p particle_handler
     * whose material has one, from the local variables of all ranks'
     * points.
     */
    void
    update(Particles::ParticleHandler<dim> &particle_handler,
           const MPI_Comm                   comm);

  private:
    const MaterialLibrary &materials;
    NonlocalGrid<dim>      grid;
    /// One material's points in this step: their properties, positions,
    /// volumes and local values.
    std::vector<double *>   points;
    std::vector<Point<dim>> locations;
    std::vector<double>     volumes, values;
  };
} // namespace MPM

#endif
