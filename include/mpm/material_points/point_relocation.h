#ifndef mpm_material_points_point_relocation_h
#define mpm_material_points_point_relocation_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_tools_cache.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/grid/background_grid.h>
#include <mpm/grid/inverse_mapping.h>
#include <mpm/grid/point_location.h>

#include <memory>
#include <set>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Finds every material point's cell and reference coordinates after the
   * points moved: the per-step point location of the MPM.
   *
   * deal.II's ParticleHandler::sort_particles_into_subdomains_and_cells()
   * inverse-maps every point through deal.II's mapping and rebuilds the
   * particle storage on every call. Most points stay in their cell from one
   * step to the next, so the 'incremental' method (the default) instead
   *  1. inverse-maps each point in its old cell with the selected inverse
   *     mapping (by default the closed form for bilinear quadrilaterals) and
   *     stores the new reference coordinates in place if the point is still
   *     inside (within reference_cell_tolerance: a point on an edge or
   *     vertex stays in the cell it was in);
   *  2. looks for each point that left its cell among the cells that share
   *     a vertex with the old cell (locate_point(): the lowest active cell
   *     index wins among the cells that contain it), then in the whole mesh;
   *  3. moves only those points (remove and insert in the ParticleHandler,
   *     which stays the store of the points; without deal.II's recount of
   *     all points unless one left the domain).
   * relocate() does all three; with the closed form (2D) the
   * grid-to-particle pass does step 1 point by point as it moves the
   * points (locate_in_cell()) and relocate_leavers() the rest.
   * A point found in no cell (neither around its old cell nor by
   * GridTools::find_active_cell_around_point() in the whole mesh, which
   * every rank's triangulation covers) has crossed the boundary. If it
   * crossed a wall of its old cell or of a cell next to it (a face on a
   * boundary with a velocity condition, set_walls()) by at most 'Wall
   * overshoot tolerance' of the cell, it is put back onto that face
   * (put_back_onto_wall()): the mesh
   * conforms to the ground, so a point sliding along it that dips below
   * the piecewise-(bi)linear surface by a millimetre is outside the mesh,
   * and the nodal velocities it moves with are tangent to the nodes'
   * averaged normals, not to the faces between them (a point just past a
   * node where the ground turns away, or on a twisted face, moves into
   * it). Otherwise it has left the domain: it is reported
   * through the ParticleHandler's particle_lost signal, as deal.II's sort
   * would report it, and removed; whoever listens decides (the Simulator
   * stops the run or counts the point's mass). If any point, on any rank,
   * moved into a cell this rank does not own, the step falls back to
   * sort_particles_into_subdomains_and_cells(), which sends points to
   * their ranks. deal.II's sort is not used to find points otherwise: on a
   * strongly distorted mesh it reports points inside the mesh as lost
   * (doc/point_location.md).
   *
   * 'sort' always calls deal.II's function, for comparison.
   */
  template <int dim>
  class PointRelocation
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Read the entries of the subsection "Material points".
     */
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * Build the vertex-to-cell map and the inverse mapping for @p grid.
     * Call again after the mesh changes.
     */
    void
    initialize(const BackgroundGrid<dim> &grid);

    /**
     * The boundary ids of the walls: the boundaries whose velocity
     * condition keeps material from crossing them (every type but
     * 'free'), onto which a point that crossed one by a little is put
     * back (see the class documentation).
     */
    void
    set_walls(const std::set<types::boundary_id> &wall_ids)
    {
      walls = wall_ids;
    }

    /**
     * Update the cells and reference locations of all points of
     * @p particle_handler after their positions changed.
     */
    void
    relocate(Particles::ParticleHandler<dim> &particle_handler);

    /**
     * Rebuild the storage (reorder_storage()) and start counting the moved
     * points afresh, as a restart does. Called before a checkpoint is
     * written: the order of the points decides the order of the sums of
     * every pass, and it depends on the storage's history (deal.II
     * appends a cell that receives its first point at the end of its list;
     * the reorderings come every reorder_fraction of the points moved, a
     * count that is not checkpointed). Without this a resumed run
     * reordered at other steps than the run through and differed at
     * round-off; with it both continue from the same storage and reorder
     * at the same steps: bit-identical (test
     * landslide_valley_3d_short_resume_identical). A run without
     * checkpoints differs from both at round-off.
     */
    void
    prepare_for_checkpoint(Particles::ParticleHandler<dim> &particle_handler);

    using ParticleIterator =
      typename Particles::ParticleHandler<dim>::particle_iterator;

    /**
     * Whether step 1 (each point in its old cell) can instead be done by
     * whoever moves the points, point by point, through locate_in_cell():
     * with 'incremental' location and the closed-form inverse mapping (2D
     * only). The grid-to-particle pass then inverse-maps each point with
     * its new position still at hand, which saves a whole pass over the
     * points and their storage (a tenth of a step of the flume, most of it
     * deal.II's per-point iteration); relocate_leavers() does the rest.
     */
    bool
    can_locate_while_moving() const
    {
      return dim == 2 && incremental &&
             inverse_type == InverseMappingType::closed_form;
    }

    /**
     * What step 1 of relocate() found for a range of points: those outside
     * their old cell, in the order they were seen, and how many points it
     * saw. Kept per chunk of points by a threaded pass (for_each_chunk())
     * and handed to add_located() in chunk order.
     */
    struct Located
    {
      std::vector<ParticleIterator> leavers;
      unsigned long long            n_points = 0;
    };

    /**
     * Step 1 of relocate() for one point that has just moved to @p x and
     * whose (old) cell has the bilinear map @p map: store its new
     * reference coordinates if it is still inside, otherwise add it to
     * @p located's leavers. Only if can_locate_while_moving(); then every
     * point must pass through here, and its range to add_located(), before
     * relocate_leavers(). Safe on several threads for different points.
     */
    static void
    locate_in_cell(const BilinearCellMap &map,
                   ParticleIterator        point,
                   const Point<dim>       &x,
                   Located                &located)
    {
      if constexpr (dim == 2)
        {
          Point<2> xi;
          if (map.contains(x, xi))
            point->set_reference_location(xi);
          else
            located.leavers.push_back(point);
          ++located.n_points;
        }
      else
        {
          (void)map;
          (void)point;
          (void)x;
          (void)located;
          Assert(false, ExcInternalError());
        }
    }

    /// Take over what locate_in_cell() found for a range of points (the
    /// ranges in the order of the points).
    void
    add_located(Located &located)
    {
      leavers_of_this_step.insert(leavers_of_this_step.end(),
                                  located.leavers.begin(),
                                  located.leavers.end());
      stats.n_points_mapped += located.n_points;
      located = Located();
    }

    /**
     * Steps 2 and 3 of relocate() for the points that step 1 (in relocate()
     * or in locate_in_cell()) found outside their old cell: find their new
     * cells and move them there. Collective.
     */
    void
    relocate_leavers(Particles::ParticleHandler<dim> &particle_handler);

    /**
     * What relocate() did so far, summed over the calls (this rank).
     */
    struct Statistics
    {
      unsigned long long n_points_mapped = 0;
      unsigned long long n_points_moved  = 0;
      /// Points sent to the rank that owns their new cell.
      unsigned long long n_points_sent   = 0;
      unsigned long long n_full_sorts    = 0;
      /// Times the point storage was put back into the order of iteration.
      unsigned long long n_reorders      = 0;
      /// Wall time spent in the reorderings.
      double             reorder_seconds = 0;
      /// Points put back onto a wall they had crossed (put_back_onto_wall()).
      unsigned long long n_points_put_back = 0;
      /// The largest distance by which such a point was moved back, in
      /// metres, and in the reference coordinates of its cell (a fraction
      /// of the cell's width across the wall).
      double largest_put_back = 0;
      double largest_put_back_fraction = 0;
      /// Points moved through a periodic boundary (PeriodicBoundaries).
      unsigned long long n_points_wrapped = 0;
      /// The sum over those moves of the point's mass times its shift:
      /// the gravitational potential energy of the points' unwrapped
      /// positions is that of their positions plus gravity times this.
      Tensor<1, dim>     wrapped_mass_shift;
    };

    const Statistics &
    statistics() const
    {
      return stats;
    }

  private:
    using CellIterator = typename Triangulation<dim>::active_cell_iterator;

    /**
     * Put the points' data (position, reference position, id, properties)
     * back into consecutive memory in the order in which the passes of a
     * step visit the points (cell by cell).
     *
     * A point that changes cell is removed from the ParticleHandler and
     * inserted again, and takes whichever slot of the property pool is
     * free: after some thousand steps of a flow the points of one cell lie
     * scattered over the whole pool, and every pass of a step (which goes
     * cell by cell) reads them at random, missing the cache (the
     * grid-to-particle pass of the flume waited a quarter of its time on
     * the first load of each point's properties). deal.II's own sort
     * restores the order; the incremental relocation does it here, once
     * the points moved since the last reordering exceed reorder_fraction
     * of the points.
     */
    void
    reorder_storage(Particles::ParticleHandler<dim> &particle_handler);

    /**
     * Move @p x through a periodic boundary if it lies beyond one (the
     * point with @p properties); count the move in the statistics.
     * Returns whether it moved.
     */
    bool
    wrap(Point<dim> &x, const double *properties);

    /**
     * A point at @p x that lies in no cell of the mesh and was last in
     * @p old_cell: if it crossed one or more walls of that cell (faces on a
     * boundary in walls) by at most overshoot_tolerance in the cell's
     * reference coordinates, and no other face, set @p x onto the walls
     * (the reference coordinates across each crossed wall set to the
     * wall's, the map of the cell taken forward) and @p location to the
     * cell it then lies in (the old cell, or, if the point also crossed
     * into a neighbour along the wall, that neighbour, searched among
     * @p candidates with @p invert_in). Failing that, if it crossed the
     * walls of one of the @p candidates and no other face of it (a point
     * that slid across a concave kink of the ground, below which the old
     * cell's wall continued passes), onto those walls of the candidate
     * with the least overshoot. Returns whether it did; the point keeps
     * its velocity and every property. Counted in the statistics.
     */
    template <typename InverseMap>
    bool
    put_back_onto_wall(const CellIterator              &old_cell,
                       const InverseMap                &invert_in,
                       const std::vector<CellIterator> &candidates,
                       Point<dim>                      &x,
                       PointLocation<dim>              &location);

    /**
     * Reorder the storage after this fraction of the points moved to
     * another cell (counting a point every time it moves).
     */
    static constexpr double reorder_fraction = 0.2;

    unsigned long long n_moved_since_reorder = 0;

    bool                                   incremental = true;
    /// The boundary ids of the walls (set_walls()).
    std::set<types::boundary_id> walls;
    /// 'Wall overshoot tolerance': how far beyond a wall of its cell, in
    /// the cell's reference coordinates, a point is put back onto it.
    double overshoot_tolerance = 0.25;
    InverseMappingType                     inverse_type = InverseMappingType::closed_form;
    std::unique_ptr<InverseMapping<dim>>   inverse_mapping;
    const BackgroundGrid<dim>             *grid = nullptr;
    std::vector<std::vector<CellIterator>> cells_at_vertex;
    std::unique_ptr<GridTools::Cache<dim>> cache;
    Statistics                             stats;
    /// The points found outside their old cell in step 1 of this step.
    std::vector<ParticleIterator> leavers_of_this_step;
    /// stats.n_points_mapped at the end of the last relocate_leavers():
    /// step 1 must have seen every point since (asserted).
    unsigned long long n_mapped_at_last_relocation = 0;
  };
} // namespace MPM

#endif
