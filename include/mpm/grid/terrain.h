#ifndef mpm_grid_terrain_h
#define mpm_grid_terrain_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/grid/tria.h>

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
   */
  struct TerrainMesh
  {
    static void
    declare_parameters(ParameterHandler &prm);

    void
    parse_parameters(ParameterHandler &prm, const std::string &input_directory);

    /// Read the elevation model and build the mesh (3D only).
    void
    create(Triangulation<3> &triangulation);

    std::string    dem_file;
    unsigned int   stride = 1, layers = 4;
    double         height = 1;
    /// 'Area of interest' (map coordinates); empty for the whole grid.
    std::vector<double> area_of_interest;
    /// The ground, once create() has read it.
    ElevationModel dem;
  };
} // namespace MPM

#endif
