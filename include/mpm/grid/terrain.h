#ifndef mpm_grid_terrain_h
#define mpm_grid_terrain_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * A digital elevation model (DEM) on a regular grid: ground elevation
   * z_g(x, y) between its nodes by bilinear interpolation. Read from an
   * ESRI ASCII grid (.asc), the plain-text raster format every GIS (GDAL,
   * QGIS, ArcGIS) writes: a header of ncols, nrows, xllcorner|xllcenter,
   * yllcorner|yllcenter, cellsize and optionally NODATA_value, then nrows
   * lines of ncols elevations, the northernmost (largest y) first. Values
   * are taken at cell centres (x = xll + (i + 1/2) cellsize for a
   * 'corner' header). A GeoTIFF converts to it with
   * `gdal_translate -of AAIGrid dem.tif dem.asc` (doc/terrain.md says why
   * the code reads the text format itself instead of linking GDAL).
   */
  class ElevationModel
  {
  public:
    /**
     * Read @p file; an InputError names the file, the line and what is
     * wrong (missing header entry, too few values, a non-number). NODATA
     * values are kept as NaN: crop() may cut them away,
     * check_complete() says where one is left.
     */
    void
    read_esri_ascii(const std::string &file);

    /**
     * Read @p file by its name: an ESRI ASCII grid (.asc) by
     * read_esri_ascii(), anything else (GeoTIFF, any raster GDAL reads)
     * through GDAL, if this build has it (gdal_available()); an
     * InputError otherwise, naming the conversion that helps. The
     * coordinate system (projection_wkt) comes from GDAL, or from a .prj
     * file beside an .asc.
     */
    void
    read(const std::string &file);

    /**
     * Band 1 of a north-up raster with square cells through GDAL, NODATA
     * as NaN. Only with GDAL.
     */
    void
    read_with_gdal(const std::string &file);

    /**
     * Write a GeoTIFF (deflate-compressed, Float64, NODATA -9999) with
     * projection_wkt as its coordinate system; through @p file.new
     * renamed at the end. Only with GDAL.
     */
    void
    write_geotiff(const std::string &file) const;

    /// Whether this build reads and writes rasters through GDAL.
    static bool
    gdal_available();

    /**
     * Write the grid as an ESRI ASCII grid, its header in the style the
     * file read had (xllcenter or xllcorner), NaN as NODATA_value -9999,
     * 9 significant digits; through @p file.new renamed at the end, so
     * that a reader never sees half a file.
     */
    void
    write_esri_ascii(const std::string &file) const;

    /**
     * Keep the nodes within [x_min, x_max] x [y_min, y_max] (map
     * coordinates, a node on the rectangle's edge kept). An InputError
     * names @p parameter if fewer than 2 x 2 nodes are left.
     */
    void
    crop(const double       x_min,
         const double       y_min,
         const double       x_max,
         const double       y_max,
         const std::string &parameter);

    /**
     * An InputError naming the file, the row and column (in the file) and
     * the map position of the first NODATA node left in the grid: the
     * mesh needs the ground everywhere.
     */
    void
    check_complete() const;

    /// Whether (x, y) lies within the grid's nodes (edges included).
    bool
    covers(const double x, const double y) const
    {
      return x >= x0 && y >= y0 && x <= node_x(n_x - 1) &&
             y <= node_y(n_y - 1);
    }

    /// The x, y of the node (i, j).
    double
    node_x(const unsigned int i) const
    {
      return x0 + i * spacing;
    }
    double
    node_y(const unsigned int j) const
    {
      return y0 + j * spacing;
    }

    /// Ground elevation at (x, y), bilinear between the grid's nodes;
    /// clamped to the grid outside it.
    double
    elevation(const double x, const double y) const;

    unsigned int n_x = 0, n_y = 0;
    /// Coordinates of the node (0, 0) (south-west) and the spacing.
    double x0 = 0, y0 = 0, spacing = 1;
    /// Elevations, row-major from the south: z[j * n_x + i] at
    /// (x0 + i spacing, y0 + j spacing).
    std::vector<double> z;
    /// The file read, and the file's column and row (from the south, 0
    /// based) of node (0, 0) and its number of rows: for messages.
    std::string  file_name;
    /// The header gave the lower-left cell's centre (xllcenter).
    bool         header_at_centre = false;
    /// The coordinate system as WKT (GDAL's, or a .prj's text), empty if
    /// unknown.
    std::string  projection_wkt;
    unsigned int first_column = 0, first_row_from_south = 0, file_rows = 0;
  };


  /**
   * The background mesh of a terrain: the DEM's footprint (optionally every
   * k-th node) meshed by hexahedra in terrain-following layers, from the
   * ground up to 'Height above ground': every vertical line of vertices
   * runs from z_g(x, y) to z_g(x, y) + H, so each cell is an isoparametric
   * hexahedron whose bottom face lies on the ground. Boundary ids as a
   * colorized box: 0 (x min), 1 (x max), 2 (y min), 3 (y max), 4 (the
   * ground), 5 (the top).
   *
   * In 2D, the same along a 'Section line' through the DEM: x is the
   * distance along the line from its first point, y the elevation;
   * quadrilaterals in terrain-following layers over the ground profile
   * sampled every 'Node stride' DEM spacings. Boundary ids: 0 (the
   * section's start), 1 (its end), 2 (the ground), 3 (the top).
   */
  struct TerrainMesh
  {
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm, const std::string &input_directory);

    /// Read the elevation model and build the mesh.
    void
    create(Triangulation<3> &triangulation);

    /// Read the elevation model and build the mesh along the section.
    void
    create(Triangulation<2> &triangulation);

    /**
     * The ground's elevation at distance @p s along the section line: the
     * DEM's before create(), the mesh's ground after it (linear between
     * its vertices, which sit on the DEM), so that the height above the
     * ground is measured from the boundary the points rest on.
     */
    double
    section_elevation(const double s) const
    {
      const double length = section_length();
      if (profile.size() < 2)
        {
          const double f = length > 0 ? s / length : 0;
          return dem.elevation(section[0] + f * (section[2] - section[0]),
                               section[1] + f * (section[3] - section[1]));
        }
      const unsigned int n = profile.size() - 1;
      const double t = std::clamp(s / length * n, 0., double(n));
      const unsigned int k = std::min<unsigned int>(n - 1, static_cast<unsigned int>(t));
      return profile[k] + (t - k) * (profile[k + 1] - profile[k]);
    }

    double
    section_length() const
    {
      return std::hypot(section[2] - section[0], section[3] - section[1]);
    }

    std::string    dem_file;
    unsigned int   stride = 1, layers = 4;
    double         height = 1;
    /// 'Area of interest' (map coordinates); empty for the whole grid.
    std::vector<double> area_of_interest;
    /// 2D: 'Section line' x0, y0, x1, y1 (map coordinates), and the
    /// ground's elevation at the mesh's vertices along it (equally spaced).
    std::array<double, 4> section = {{0, 0, 0, 0}};
    std::vector<double>   profile;
    /// The ground, once create() has read it.
    ElevationModel dem;
  };
} // namespace MPM

#endif
