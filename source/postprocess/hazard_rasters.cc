#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_tools.h>

#include <mpm/base/input_error.h>
#include <mpm/grid/terrain.h>
#include <mpm/material_points/property_layout.h>
#include <mpm/postprocess/postprocessor.h>
#include <mpm/solver/simulator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace MPM
{
  namespace Postprocessors
  {
    /**
     * The maps a hazard assessment is made of, as RAMMS and r.avaflow give
     * them: on a raster over the terrain, the largest flow height, the
     * largest speed and the largest dynamic pressure over the run, and
     * the deposit's thickness at its end, written as georeferenced ESRI
     * ASCII grids (max_flow_height.asc, max_speed.asc, max_pressure.asc,
     * deposit_thickness.asc; with the elevation model's coordinate system
     * in a .prj beside each if it has one; or as GeoTIFF with GDAL) that
     * open in any GIS over the DEM.
     *
     * The raster is the elevation model's own grid (its nodes are the
     * raster's cell centres, so origin and cell size are the DEM's) or one
     * of a chosen cell size over the same extent. Each step every point
     * spreads its mass, its mass over its material's density (the volume
     * it had when released) and its momentum over the four raster nodes
     * around its map position (x, y) with bilinear weights, which add up
     * to one: the raster holds exactly the released volume. At a node,
     *  - flow height h = V / A: that volume over the node's cell area,
     *    measured vertically (a column of material, not normal to the
     *    slope), at the density of the release: a granular body that
     *    spreads into a thin layer under a tension cutoff grows in the
     *    points' own volume (J V_0), by a few per cent in the shipped
     *    landslide, without becoming thicker; the report gives that
     *    growth beside the raster's volume;
     *  - speed |sum m v| / sum m: the column's depth-averaged velocity;
     *  - pressure rho v^2, with the column's density rho = M / V;
     * maxima over every step, and the deposit is the flow height at the
     * run's end. Nodes the material never reached hold 0. The raster
     * should be coarser than the points' spacing (a node needs a few
     * points around it; a DEM of 1 m under 3 points per 1 m cell is), or
     * the flow height is noisy.
     *
     * Written at every output time (the run's last step is one); the
     * maxima are kept in checkpoints.
     */
    template <int dim>
    class HazardRasters : public PostprocessorWithState<dim, HazardRasters<dim>>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Cell size",
                          "elevation model",
                          Patterns::Anything(),
                          "'elevation model': the rasters are the DEM's grid "
                          "(Mesh/Source = terrain: the same origin, cell "
                          "size and extent, cropped as the mesh is); or a "
                          "cell size in m over the same extent (or, on "
                          "another mesh, over the mesh's horizontal "
                          "bounding box), the first cell centre at the "
                          "extent's lower-left corner.");
        prm.declare_entry("Raster format",
                          "esri ascii",
                          Patterns::Selection("esri ascii|geotiff"),
                          "'esri ascii': NAME.asc, with NAME.prj holding the "
                          "elevation model's coordinate system when it has "
                          "one; 'geotiff': NAME.tif with the coordinate "
                          "system inside (needs a build with GDAL).");
        prm.declare_entry("Deposit height threshold",
                          "0.01",
                          Patterns::Double(0),
                          "Flow height (m) above which a node counts in the "
                          "report's affected and deposit areas.");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        cell_size_setting = Utilities::trim(prm.get("Cell size"));
        if (cell_size_setting != "elevation model")
          {
            double size = 0;
            try
              {
                size = Utilities::string_to_double(cell_size_setting);
              }
            catch (...)
              {
              }
            check_input(size > 0,
                        "Postprocess/hazard rasters/Cell size = '" +
                          cell_size_setting +
                          "': give 'elevation model' or a positive cell "
                          "size in m.");
          }
        threshold = prm.get_double("Deposit height threshold");
        geotiff   = prm.get("Raster format") == "geotiff";
        check_input(!geotiff || ElevationModel::gdal_available(),
                    "Postprocess/hazard rasters/Raster format = geotiff needs "
                    "a build with GDAL (Debian: libgdal-dev, then configure "
                    "the build again); 'esri ascii' works without.");
      }

      void
      initialize() override
      {
        check_input(dim == 3,
                    "Postprocess/List of postprocessors: 'hazard rasters' "
                    "maps a 3D flow over the terrain; this scene is 2D.");
        set_up_raster();
        accumulate();
        released_volume = total_volume();
        released_point_volume = point_volume;
        released_height = *std::max_element(height.begin(), height.end());
      }

      void
      execute(const bool output_step) override
      {
        // A resumed run does not call initialize(): the raster's geometry
        // comes from the checkpoint.
        accumulate();
        if (output_step)
          write_rasters();
      }

      void
      write_report(std::ostream &report) override
      {
        const double area = raster.spacing * raster.spacing;
        double       deposit_volume = 0, largest[3] = {0, 0, 0};
        unsigned int affected = 0, deposit_nodes = 0;
        for (std::size_t k = 0; k < height.size(); ++k)
          {
            deposit_volume += height[k] * area;
            largest[0] = std::max(largest[0], max_height[k]);
            largest[1] = std::max(largest[1], max_speed[k]);
            largest[2] = std::max(largest[2], max_pressure[k]);
            affected += max_height[k] > threshold;
            deposit_nodes += height[k] > threshold;
          }
        report << std::setprecision(9)
               << "## hazard rasters: " << raster.n_x << " x " << raster.n_y
               << " nodes, cell size " << raster.spacing
               << " m, first node (map) " << raster.x0 << ", " << raster.y0
               << "\n"
               << std::setprecision(6)
               << "released volume (m^3): " << released_volume
               << "\ndeposit raster volume (m^3): " << deposit_volume
               << "\ndeposit / released - 1: "
               << deposit_volume / released_volume - 1
               << "\npoints' own volume (J V0) now / at the release - 1: "
               << point_volume / released_point_volume - 1
               << "\nlargest flow height at the release (m): "
               << released_height
               << "\nlargest flow height (m): " << largest[0]
               << "\nlargest speed (m/s): " << largest[1]
               << "\nlargest pressure (kPa): " << largest[2] / 1000
               << "\narea reached by more than " << threshold
               << " m of flow (m^2): " << affected * area
               << "\ndeposit area thicker than " << threshold
               << " m (m^2): " << deposit_nodes * area << '\n';
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar & raster.n_x & raster.n_y & raster.x0 & raster.y0 &
          raster.spacing & raster.header_at_centre & raster.projection_wkt &
          height & max_height &
          max_speed & max_pressure & released_volume & released_point_volume &
          released_height & last_window;
      }

    private:
      /// The raster's geometry from the DEM, a cell size, or the mesh.
      void
      set_up_raster()
      {
        const ElevationModel *dem = this->get_grid().elevation_model();
        if (dem != nullptr && cell_size_setting == "elevation model")
          {
            raster   = *dem;
            raster.z.clear();
          }
        else
          {
            check_input(cell_size_setting != "elevation model",
                        "Postprocess/hazard rasters/Cell size = elevation "
                        "model, but the mesh is not built on one "
                        "(Mesh/Source = terrain): give a cell size in m.");
            double lower[2], upper[2];
            if (dem != nullptr)
              {
                lower[0] = dem->x0;
                lower[1] = dem->y0;
                upper[0] = dem->node_x(dem->n_x - 1);
                upper[1] = dem->node_y(dem->n_y - 1);
              }
            else
              {
                const auto &grid = this->get_grid();
                const auto  box =
                  GridTools::compute_bounding_box(grid.triangulation);
                const Point<dim> a =
                  grid.to_scene_frame(box.get_boundary_points().first);
                const Point<dim> b =
                  grid.to_scene_frame(box.get_boundary_points().second);
                const MPI_Comm comm = this->get_mpi_communicator();
                for (unsigned int d = 0; d < 2; ++d)
                  {
                    lower[d] = Utilities::MPI::min(std::min(a[d], b[d]), comm);
                    upper[d] = Utilities::MPI::max(std::max(a[d], b[d]), comm);
                  }
              }
            raster.spacing = Utilities::string_to_double(cell_size_setting);
            raster.x0      = lower[0];
            raster.y0      = lower[1];
            raster.n_x =
              1 + static_cast<unsigned int>(
                    std::ceil((upper[0] - lower[0]) / raster.spacing - 1e-9));
            raster.n_y =
              1 + static_cast<unsigned int>(
                    std::ceil((upper[1] - lower[1]) / raster.spacing - 1e-9));
            raster.header_at_centre = dem != nullptr && dem->header_at_centre;
            raster.projection_wkt =
              dem != nullptr ? dem->projection_wkt : std::string();
          }
        const std::size_t n = std::size_t(raster.n_x) * raster.n_y;
        height.assign(n, 0.);
        max_height.assign(n, 0.);
        max_speed.assign(n, 0.);
        max_pressure.assign(n, 0.);
      }

      /**
       * Spread the points over the raster's nodes and update the maxima.
       * Only the window of nodes the points reach this step is summed,
       * exchanged between ranks and updated (a DEM of 10^6 nodes under a
       * slide of a few hundred costs what the slide's footprint costs);
       * the flow height is set to zero where the last window was.
       */
      void
      accumulate()
      {
        using Layout           = PropertyLayout<dim>;
        const auto    &grid      = this->get_grid();
        const MPI_Comm comm      = this->get_mpi_communicator();
        const auto    &materials = this->get_materials();
        // Each point's lower-left node (i, j) and weights; the window.
        struct Spread
        {
          unsigned int   i, j;
          double         fs, ft, volume, mass;
          Tensor<1, dim> momentum;
        };
        std::vector<Spread> spreads;
        spreads.reserve(
          this->get_particle_handler().n_locally_owned_particles());
        // Window: -i_min, -j_min, i_max, j_max (one max() for all four).
        double window[4] = {-double(raster.n_x), -double(raster.n_y), -1, -1};
        double own_volume = 0;
        for (const auto &point : this->get_particle_handler())
          {
            const Point<dim> x = grid.to_scene_frame(point.get_location());
            const double s = std::clamp((x[0] - raster.x0) / raster.spacing,
                                        0.,
                                        raster.n_x - 1.);
            const double t = std::clamp((x[1] - raster.y0) / raster.spacing,
                                        0.,
                                        raster.n_y - 1.);
            Spread p;
            p.i = std::min<unsigned int>(raster.n_x - 2, static_cast<unsigned int>(s));
            p.j = std::min<unsigned int>(raster.n_y - 2, static_cast<unsigned int>(t));
            p.fs             = s - p.i;
            p.ft             = t - p.j;
            const auto props = point.get_properties();
            p.mass           = props[Layout::mass];
            p.volume =
              p.mass /
              materials[static_cast<unsigned int>(props[Layout::material_id])]
                .density;
            p.momentum = p.mass * read_vector<dim>(&props[Layout::velocity]);
            own_volume += props[Layout::volume];
            window[0] = std::max(window[0], -double(p.i));
            window[1] = std::max(window[1], -double(p.j));
            window[2] = std::max(window[2], double(p.i + 1));
            window[3] = std::max(window[3], double(p.j + 1));
            spreads.push_back(p);
          }
        Utilities::MPI::max(ArrayView<const double>(window, 4),
                            comm,
                            ArrayView<double>(window, 4));
        point_volume = Utilities::MPI::sum(own_volume, comm);

        // The flow height is zero outside this step's window.
        for (unsigned int j = last_window[1]; j < last_window[3]; ++j)
          for (unsigned int i = last_window[0]; i < last_window[2]; ++i)
            height[std::size_t(j) * raster.n_x + i] = 0;
        if (window[2] < 0)
          {
            last_window = {{0, 0, 0, 0}};
            return;
          }
        const unsigned int i0 = -window[0], j0 = -window[1];
        const unsigned int w  = window[2] + 1 - i0, h = window[3] + 1 - j0;
        const std::size_t  n  = std::size_t(w) * h;
        last_window           = {{i0, j0, i0 + w, j0 + h}};

        // Volume at the release density, mass, then the momentum's dim
        // components, per node of the window.
        std::vector<double> sums((2 + dim) * n, 0.);
        for (const auto &p : spreads)
          {
            const double weights[4] = {(1 - p.fs) * (1 - p.ft),
                                       p.fs * (1 - p.ft),
                                       (1 - p.fs) * p.ft,
                                       p.fs * p.ft};
            const std::size_t base = std::size_t(p.j - j0) * w + (p.i - i0);
            const std::size_t nodes[4] = {base, base + 1, base + w, base + w + 1};
            for (unsigned int k = 0; k < 4; ++k)
              {
                sums[nodes[k]] += weights[k] * p.volume;
                sums[n + nodes[k]] += weights[k] * p.mass;
                for (unsigned int d = 0; d < dim; ++d)
                  sums[(2 + d) * n + nodes[k]] += weights[k] * p.momentum[d];
              }
          }
        if (Utilities::MPI::n_mpi_processes(comm) > 1)
          Utilities::MPI::sum(ArrayView<const double>(sums.data(), sums.size()),
                              comm,
                              ArrayView<double>(sums.data(), sums.size()));
        const double area = raster.spacing * raster.spacing;
        for (unsigned int b = 0; b < h; ++b)
          for (unsigned int a = 0; a < w; ++a)
            {
              const std::size_t local = std::size_t(b) * w + a;
              const std::size_t k = std::size_t(j0 + b) * raster.n_x + i0 + a;
              const double volume = sums[local], mass = sums[n + local];
              height[k]           = volume / area;
              max_height[k]       = std::max(max_height[k], height[k]);
              if (mass > 0)
                {
                  double momentum_squared = 0;
                  for (unsigned int d = 0; d < dim; ++d)
                    momentum_squared +=
                      sums[(2 + d) * n + local] * sums[(2 + d) * n + local];
                  const double speed = std::sqrt(momentum_squared) / mass;
                  max_speed[k]       = std::max(max_speed[k], speed);
                  max_pressure[k] =
                    std::max(max_pressure[k], mass / volume * speed * speed);
                }
            }
      }

      double
      total_volume() const
      {
        double volume = 0;
        for (const double h : height)
          volume += h * raster.spacing * raster.spacing;
        return volume;
      }

      void
      write_rasters()
      {
        if (Utilities::MPI::this_mpi_process(this->get_mpi_communicator()) != 0)
          return;
        const std::string &directory = this->get_output_directory();
        const std::pair<const char *, const std::vector<double> *> maps[] = {
          {"max_flow_height", &max_height},
          {"max_speed", &max_speed},
          {"max_pressure", &max_pressure},
          {"deposit_thickness", &height}};
        ElevationModel out = raster;
        for (const auto &[name, values] : maps)
          {
            out.z = *values;
            if (geotiff)
              out.write_geotiff(directory + name + ".tif");
            else
              {
                out.write_esri_ascii(directory + name + ".asc");
                if (!raster.projection_wkt.empty())
                  std::ofstream(directory + name + ".prj")
                    << raster.projection_wkt;
              }
          }
      }

      std::string cell_size_setting = "elevation model";
      double      threshold         = 0.01;
      /// The raster's geometry (its z unused).
      ElevationModel raster;
      /// 'Raster format = geotiff'.
      bool geotiff = false;
      /// Flow height now (m), and the maxima of height (m), speed (m/s)
      /// and pressure (Pa) so far, per node, row-major from the south.
      std::vector<double> height, max_height, max_speed, max_pressure;
      /// The raster's volume at the start (m^3), the points' own volume
      /// then and now.
      double released_volume = 0, released_point_volume = 0,
             point_volume = 0;
      /// The largest flow height at the start (m).
      double released_height = 0;
      /// The window of nodes the last step touched: i_begin, j_begin,
      /// i_end, j_end.
      std::array<unsigned int, 4> last_window = {{0, 0, 0, 0}};
    };
  } // namespace Postprocessors
} // namespace MPM

MPM_REGISTER_POSTPROCESSOR(MPM::Postprocessors::HazardRasters,
                           "hazard rasters",
                           "maximum flow height, speed and pressure and the deposit thickness on a raster over the terrain, written as ESRI ASCII grids.")
