#ifndef mpm_grid_background_grid_h
#define mpm_grid_background_grid_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <mpm/grid/bilinear_cell_map.h>
#include <mpm/grid/extruded_cell_map.h>
#include <mpm/grid/parallelepiped_map.h>
#include <mpm/grid/periodic_boundaries.h>
#include <mpm/grid/terrain.h>

#include <array>
#include <string>

namespace MPM
{
  using namespace dealii;

  /**
   * The Eulerian background mesh: a p4est-distributed triangulation of
   * (possibly irregular) quadrilaterals or hexahedra, the bilinear
   * isoparametric mapping MappingQ1, and the FE_Q(1)^dim DoFHandler whose
   * degrees of freedom are the nodal vector fields (momentum, force,
   * velocity) of the MPM step. Vertex ordering and reference cell are
   * deal.II's: the unit square [0,1]^dim with vertices in lexicographic
   * order.
   *
   * The mesh comes either from a Gmsh .msh file (boundary ids from the
   * physical tags of the boundary lines, material ids from the physical tags
   * of the surfaces) or from a GridGenerator function named in the
   * parameter file.
   */
  template <int dim>
  class BackgroundGrid
  {
  public:
    explicit BackgroundGrid(const MPI_Comm comm);

    static void
    declare_parameters(ParameterHandler &prm);

    /**
     * Read the "Mesh" subsection. @p input_directory is the directory of
     * the .prm file, against which a relative mesh file name is resolved.
     */
    void
    parse_parameters(ParameterHandler &prm, const std::string &input_directory);

    /**
     * Build the triangulation and distribute the degrees of freedom.
     */
    void
    create();

    /**
     * Everything that depends on which cells this rank owns or sees: the
     * degrees of freedom, their index sets and the sizes of the locally
     * relevant cells. Called by create(), and again after the
     * triangulation was repartitioned or loaded from a checkpoint.
     */
    void
    setup_partition_data();

    /**
     * Smallest edge length over the whole mesh.
     */
    double
    minimum_cell_size() const
    {
      return min_cell_size;
    }

    /**
     * Shortest edge of each locally relevant active cell, indexed by
     * active_cell_index(): the CFL length of the cells that hold points,
     * computed once, so that small cells far from the material (a mesh
     * graded away from the ground) do not shorten the time step.
     */
    double
    cell_size(const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return cell_size(cell->active_cell_index());
    }

    /// cell_size() of the cell with active_cell_index() @p index.
    double
    cell_size(const unsigned int index) const
    {
      return cell_sizes[index];
    }

    /**
     * The vertices of each locally relevant active cell in deal.II's order,
     * indexed by active_cell_index(). Every step inverse-maps and evaluates
     * shape functions cell by cell; reading the vertices through the
     * triangulation (cell->vertex(), which goes through the cell's lines)
     * cost more than the inverse map itself once the material had spread
     * to a few points per cell. The mesh does not move, so they are copied
     * once.
     */
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell> &
    cell_vertices(
      const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return vertices_of_cells[cell->active_cell_index()];
    }

    /// cell_vertices() of the cell with active_cell_index() @p index.
    const std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell> &
    cell_vertices(const unsigned int index) const
    {
      return vertices_of_cells[index];
    }

    /**
     * The bilinear map of each locally relevant active cell in the form
     * the closed-form inverse mapping and the shape functions use it,
     * indexed by active_cell_index(); computed once, like the vertices.
     * 2D only (empty in 3D).
     */
    const BilinearCellMap &
    bilinear_map(
      const typename Triangulation<dim>::active_cell_iterator &cell) const
    {
      return bilinear_map(cell->active_cell_index());
    }

    /// bilinear_map() of the cell with active_cell_index() @p index.
    const BilinearCellMap &
    bilinear_map(const unsigned int index) const
    {
      AssertIndexRange(index, bilinear_maps.size());
      return bilinear_maps[index];
    }

    /**
     * The affine map of each locally relevant active cell that is a
     * parallelepiped (ParallelepipedMap::is_affine(); not affine for the
     * others), by active_cell_index(); computed once. 3D only (empty in
     * 2D, where bilinear_map() has the parallelogram case).
     */
    const ParallelepipedMap &
    parallelepiped_map(const unsigned int index) const
    {
      AssertIndexRange(index, parallelepiped_maps.size());
      return parallelepiped_maps[index];
    }

    /**
     * The closed-form inverse map of the locally relevant active cell with
     * active_cell_index() @p index if it is extruded (ExtrudedCellMap:
     * terrain columns), nullptr for any other cell and in 2D. Computed
     * once; stored only for the extruded cells.
     */
    const ExtrudedCellMap *
    extruded_map(const unsigned int index) const
    {
      if (extruded_map_index.empty())
        return nullptr;
      AssertIndexRange(index, extruded_map_index.size());
      const unsigned int k = extruded_map_index[index];
      return k == numbers::invalid_unsigned_int ? nullptr : &extruded_maps[k];
    }

    /**
     * @name Scene rotation.
     * The parameter file describes a scene in its own frame; "Mesh/Scene
     * rotation angle" turns the whole scene (about "Scene rotation axis"
     * in 3D) so
     * that the same case can be run in any orientation: the mesh is rotated
     * when it is created, and every position, vector and tensor given in
     * the parameter file (point regions, gravity, initial velocity and
     * stress, given boundary normals) is rotated with it by the classes that
     * read them, through these functions. This is how the tests prove that
     * the node-frame machinery does not depend on the orientation.
     * @{
     */
    /// From the parameter file's frame to the mesh's: R x.
    Tensor<1, dim>
    to_mesh_frame(const Tensor<1, dim> &v) const
    {
      return rotation * v;
    }

    /// A position: R (x - o), o the local origin.
    Point<dim>
    to_mesh_frame(const Point<dim> &x) const
    {
      if (has_local_origin)
        return Point<dim>(rotation * (x - local_origin));
      return Point<dim>(rotation * x);
    }

    /// A gradient (of a vector field) in the mesh's frame: R G R^T.
    Tensor<2, dim>
    to_mesh_frame(const Tensor<2, dim> &G) const
    {
      return rotation * G * transpose(rotation);
    }

    /// R sigma R^T for a 3x3 stress (plane strain in 2D).
    SymmetricTensor<2, 3>
    to_mesh_frame(const SymmetricTensor<2, 3> &t) const;

    /// A vector from the mesh's frame back to the parameter file's: R^T v.
    Tensor<1, dim>
    to_scene_frame(const Tensor<1, dim> &v) const
    {
      return transpose(rotation) * v;
    }

    /// A position from the mesh's frame back to the parameter file's:
    /// R^T x + o.
    Point<dim>
    to_scene_frame(const Point<dim> &x) const
    {
      if (has_local_origin)
        return Point<dim>(transpose(rotation) * x) + local_origin;
      return Point<dim>(transpose(rotation) * x);
    }

    /// R^T sigma R: a stress back to the parameter file's frame.
    SymmetricTensor<2, 3>
    to_scene_frame(const SymmetricTensor<2, 3> &t) const;

    bool
    is_rotated() const
    {
      return rotation_angle != 0;
    }

    /**
     * The local origin o ('Mesh/Local origin'): the mesh lives at x - o
     * while the parameter file, the elevation model and the outputs in
     * map coordinates speak of x. Zero unless the scene lies far from
     * the coordinates' zero (a DEM in UTM coordinates), where positions
     * of 10^6 m would leave the inverse mapping and single-precision
     * output (VTU) too few digits for a cell.
     */
    const Tensor<1, dim> &
    get_local_origin() const
    {
      return local_origin;
    }
    /** @} */

    /**
     * Height of @p x (mesh frame) above the ground: z - z_g(x, y) on a
     * terrain mesh (Mesh/Source = terrain; in 2D the ground along the
     * section line), the last coordinate otherwise.
     * Point regions use it ('h' in a region function), so that a soil
     * layer of given depth on a hillside is one expression.
     */
    double
    height_above_ground(const Point<dim> &x) const
    {
      if (source == "terrain")
        {
          const Point<dim> map_x = has_local_origin ? x + local_origin : x;
          if constexpr (dim == 2)
            return map_x[1] - terrain.section_elevation(map_x[0]);
          else
            return map_x[dim - 1] - terrain.dem.elevation(map_x[0], map_x[1]);
        }
      return x[dim - 1];
    }

    /// The ground of a terrain mesh (map coordinates), nullptr for any
    /// other source.
    const ElevationModel *
    elevation_model() const
    {
      return source == "terrain" ? &terrain.dem : nullptr;
    }

    parallel::distributed::Triangulation<dim> triangulation;
    MappingQ1<dim>                            mapping;
    FESystem<dim>                             fe;
    DoFHandler<dim>                           dof_handler;
    IndexSet                                  locally_owned_dofs;
    IndexSet                                  locally_relevant_dofs;
    /// 'Mesh/Periodic boundaries' (none by default).
    PeriodicBoundaries<dim>                   periodic_boundaries;

  private:
    void
    create_subdivided_hyper_rectangle();

    /**
     * Stop with an InputError if a cell's isoparametric map is not
     * invertible: a non-convex (arrowhead), self-intersecting or
     * zero-area quadrilateral. The inverse mapping of the material points
     * and the shape function gradients divide by the Jacobian determinant,
     * which changes sign inside such a cell; deal.II reads these meshes
     * without complaint (it only reorients clockwise cells). For a
     * multilinear cell the determinant is positive everywhere if it is
     * positive at every vertex, so the check is exact and costs one
     * determinant per vertex. Every rank checks its own cells; all stop
     * with the same message.
     */
    void
    check_cell_geometry() const;

    MPI_Comm     mpi_communicator;
    std::string  source;
    std::string  mesh_file;
    std::string  generator_name;
    /// Mesh/Source = terrain: the elevation model and the layers over it.
    TerrainMesh  terrain;
    std::string  generator_arguments;
    unsigned int n_global_refinements = 0;
    /// Fraction of the shortest adjacent edge by which interior vertices
    /// are moved at random.
    double vertex_perturbation = 0;
    /// Scene rotation angle (radians) and its matrix.
    double         rotation_angle = 0;
    /// Axis of the scene rotation (3D; +z or -z in 2D).
    Tensor<1, 3>   rotation_axis;
    Tensor<2, dim> rotation       = unit_symmetric_tensor<dim>();
    /// 'Mesh/Local origin' as given ('auto' or coordinates), and the
    /// origin create() chose from it.
    std::string    local_origin_setting = "auto";
    Tensor<1, dim> local_origin;
    bool           has_local_origin = false;
    double       min_cell_size        = 0;
    std::vector<double> cell_sizes;
    std::vector<std::array<Point<dim>, GeometryInfo<dim>::vertices_per_cell>>
      vertices_of_cells;
    std::vector<BilinearCellMap>   bilinear_maps;
    std::vector<ParallelepipedMap> parallelepiped_maps;
    /// extruded_map(): each cell's position in extruded_maps (or
    /// numbers::invalid_unsigned_int), and the maps of the extruded cells.
    std::vector<unsigned int>    extruded_map_index;
    std::vector<ExtrudedCellMap> extruded_maps;
  };
} // namespace MPM

#endif
