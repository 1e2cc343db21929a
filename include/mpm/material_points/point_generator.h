#ifndef mpm_material_points_point_generator_h
#define mpm_material_points_point_generator_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/point.h>

#include <deal.II/particles/particle_handler.h>

#include <mpm/grid/background_grid.h>
#include <mpm/material_points/release_area.h>
#include <mpm/materials/material_library.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * Creates the material points of a scene from regions described in the
   * parameter file:
   *
   *   subsection Material points
   *     set List of regions = block
   *     subsection block
   *       set Type = box            # box | polygon | cells | file
   *       set Box  = 0, 0 : 1, 1
   *       set Points per cell = 4   # per direction
   *       set Material = rock
   *       set Initial velocity = 0; 0
   *       set Initial stress = geostatic
   *
   * Box, polygon and cells regions place n^dim points per cell at the
   * centres of an n x n sub-grid of the reference cell; each point gets the
   * volume of its part of the cell (det J times the sub-cell weight, so the
   * volumes of a cell's points add up to the cell's area exactly) and the
   * mass density times that volume. A point belongs to a box or polygon
   * region if its position lies inside it, so a region that does not
   * conform to the mesh is approximated to within a sub-cell.
   */
  /**
   * What the geostatic stress of a saturated material needs of the pore
   * water (PoreWater::initial_state()): its density, the pore pressure
   * at a point of the scene at the start (compression positive), and the
   * density of the still water the scene is submerged in ('Pore water/
   * Submerged'; 0: not submerged), whose buoyancy the effective stress
   * does not carry (the pore pressure is then the excess over its
   * hydrostatic pressure).
   */
  template <int dim>
  struct InitialPoreWater
  {
    double                                    density = 0;
    std::function<double(const Point<dim> &)> pressure;
    double                                    ambient_density = 0;
  };


  template <int dim>
  class PointGenerator
  {
  public:
    static void
    declare_name_list(ParameterHandler &prm);

    static std::vector<std::string>
    read_name_list(ParameterHandler &prm);

    static void
    declare_parameters(ParameterHandler               &prm,
                       const std::vector<std::string> &names);

    void
    parse_parameters(ParameterHandler      &prm,
                     const MaterialLibrary &materials,
                     const std::string     &input_directory);

    /**
     * Insert the points of every region into @p particle_handler, with
     * globally unique ids 0, 1, ... (ordered by rank, then region, then
     * cell). @p gravity (in the scene's frame, see
     * BackgroundGrid::to_mesh_frame()) is needed for the geostatic initial
     * stress. If @p velocity_gradient_slot is a property slot, the
     * gradient of the initial velocity at each point is written there
     * (dim x dim, row-major; APIC's affine matrix starts from it, so that
     * a body set spinning keeps its sub-cell motion from the first step).
     * Returns each region's number of points, volume and mass (the
     * released volume of a release area).
     *
     * A saturated material's geostatic stress is the effective one: the
     * weight of the saturated mixture above, (rho_d + n rho_w) g depth,
     * less the pore pressure @p pore_water says the point starts with
     * (with the water table at the surface, the buoyant weight).
     */
    /// What generate() created for one region (global sums).
    struct RegionSummary
    {
      std::string           name;
      types::particle_index n_points = 0;
      /// m^3 (m^2 per unit thickness in 2D) and kg.
      double volume = 0, mass = 0;
    };

    std::vector<RegionSummary>
    generate(const BackgroundGrid<dim>      &grid,
             const MaterialLibrary          &materials,
             const Tensor<1, dim>           &gravity,
             Particles::ParticleHandler<dim> &particle_handler,
             const unsigned int velocity_gradient_slot =
               numbers::invalid_unsigned_int,
             const InitialPoreWater<dim> &pore_water = {}) const;

    /**
     * A region that reaches beyond the mesh through an open boundary: its
     * name, the area of open boundary it crosses and, for box and polygon
     * regions, the volume the region has beyond the mesh (region volume
     * minus the volume of its points; -1 where the region's volume is not
     * known in closed form).
     */
    struct RegionBeyondMesh
    {
      std::string name;
      double      crossed_area = 0;
      double      volume_lost  = -1;
    };

    /**
     * The regions (box, polygon, function) that continue beyond the mesh
     * through a boundary whose id is not in @p constrained_ids, i.e. that
     * no boundary condition holds material against: there the material
     * the region describes beyond the mesh is simply not created (a
     * landslide given 2 m deep over a meshed layer 1 m thick ran with half
     * of its mass). A region that continues through a constrained
     * boundary (a bed, a symmetry plane) is cut there on purpose.
     * Checked at the centre of each open boundary face, just outside it.
     * Collective.
     */
    std::vector<RegionBeyondMesh>
    regions_beyond_mesh(const BackgroundGrid<dim>             &grid,
                        const std::set<types::boundary_id> &constrained_ids) const;

  private:
    struct Region
    {
      std::string                 name;
      std::string                 type;
      Point<dim>                  box_lower, box_upper;
      /// Type = polygon: the footprint and, in 3D, the release depth.
      ReleaseArea                 release_area;
      unsigned int                cell_material_id = 0;
      std::string                 file_name;
      unsigned int                points_per_cell = 2;
      unsigned int                material_index  = 0;
      std::string                 initial_stress;
      double                      k0 = -1;
      double                      surface_elevation = 0;
      bool                        automatic_surface = true;
      std::shared_ptr<Functions::ParsedFunction<dim>> initial_velocity;
      std::shared_ptr<Functions::ParsedFunction<dim>> initial_stress_function;
      /// Type = function: positive inside; its time variable is h.
      std::shared_ptr<FunctionParser<dim>> inside;

      /// Whether the point @p p (scene frame), at height @p h above the
      /// ground, belongs to the region (cells: always).
      bool
      contains(const Point<dim> &p, const double h) const;
    };

    struct NewPoint
    {
      Point<dim>                                         location;
      Point<dim>                                         reference_location;
      typename Triangulation<dim>::active_cell_iterator cell;
      double                                             volume;
      /// Initial stress read from the point file (scene frame).
      SymmetricTensor<2, 3> stress;
    };

    std::vector<NewPoint>
    points_of_region(const Region &region, const BackgroundGrid<dim> &grid) const;

    std::vector<Region> regions;
  };
} // namespace MPM

#endif
