#ifndef mpm_material_points_release_area_h
#define mpm_material_points_release_area_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <mpm/grid/terrain.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace MPM
{
  using namespace dealii;

  /**
   * The region of a 'Type = polygon' entry of 'Material points': a
   * footprint of one or more polygons in the horizontal (x, y) plane, in
   * map coordinates, and in 3D how deep the material stands over it, as
   * hazard practice gives a release (RAMMS, r.avaflow): a release polygon
   * and a release depth.
   *
   * The footprint is listed in the parameter file ('Polygon') or read from
   * a 'Polygon file': GeoJSON (every Polygon and MultiPolygon of its
   * features, the format QGIS and GDAL's ogr2ogr write) by the code
   * itself, a shapefile or any vector format OGR reads in a build with
   * GDAL.
   * Inside is decided by the even-odd rule over all rings, so holes and
   * several polygons need nothing special.
   *
   * In 3D the material fills the footprint from the ground up to
   * - a 'Release depth' in m (vertical), or
   * - a raster of depths ('Release depth' = an ESRI ASCII grid), or
   * - a raster of the top surface ('Release top surface'): the body is
   *   what lies between the mesh's ground and that surface, e.g. the
   *   pre-failure terrain over a bed whose elevation model has the failure
   *   surface cut in (the convention of r.avaflow, whose elevation is the
   *   bottom of the flow).
   * Outside a raster's extent, and at its NODATA nodes, nothing is
   * released. In 2D 'Polygon' is the region itself (x, y).
   */
  class ReleaseArea
  {
  public:
    /// The entries, inside the region's subsection.
    static void
    declare_parameters(ParameterHandler &prm, const unsigned int dim);

    /// Read them; @p path ('Material points/NAME/') names them in errors.
    void
    parse_parameters(ParameterHandler  &prm,
                     const unsigned int dim,
                     const std::string &path,
                     const std::string &input_directory);

    /// Whether (x, y) lies in the footprint (even-odd over all rings).
    bool
    footprint_contains(const double x, const double y) const;

    /**
     * Whether a point at map position @p x, @p h above the ground, is
     * released: in the footprint and, in 3D, below the release depth or
     * the top surface.
     */
    template <int dim>
    bool
    contains(const Point<dim> &x, const double h) const;

    /// The footprint's bounding box: lower x, y, upper x, y.
    std::array<double, 4>
    footprint_bounds() const;

    /// The area of the footprint (m^2; the rings' areas with the sign the
    /// even-odd rule gives them: valid for disjoint polygons with holes).
    double
    footprint_area() const;

    /**
     * The rings of every Polygon and MultiPolygon in the GeoJSON file @p
     * file; an InputError names the file and what is missing.
     */
    static std::vector<std::vector<Point<2>>>
    read_geojson(const std::string &file);

    /**
     * The rings of every polygon in a vector file that GDAL/OGR reads
     * (a shapefile, GeoPackage, ...; all layers). Only in a build with
     * GDAL (ElevationModel::gdal_available()).
     */
    static std::vector<std::vector<Point<2>>>
    read_with_gdal(const std::string &file);

  private:
    std::vector<std::vector<Point<2>>> rings;
    /// Constant depth (m), if no raster is given.
    double depth = 0;
    /// A raster of depths, or of the top surface's elevation.
    std::shared_ptr<ElevationModel> depth_raster, top_surface;
  };
} // namespace MPM

#endif
