#include <deal.II/base/utilities.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/material_points/release_area.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace MPM
{
  void
  ReleaseArea::declare_parameters(ParameterHandler &prm, const unsigned int dim)
  {
    prm.declare_entry("Polygon",
                      "0, 0 ; 1, 0 ; 1, 1 ; 0, 1",
                      Patterns::Anything(),
                      "Type = polygon: vertices x, y (m, map coordinates in "
                      "3D) separated by ';'. In 2D the region itself, in 3D "
                      "the footprint of a release area (see 'Release "
                      "depth'). Ignored if 'Polygon file' is given.");
    prm.declare_entry("Polygon file",
                      "",
                      Patterns::FileName(),
                      "Type = polygon: a GeoJSON file (.geojson, .json; or "
                      "with GDAL a shapefile or any vector file OGR reads) "
                      "whose polygons (all rings, even-odd rule: holes are "
                      "holes) make the footprint, in the elevation model's "
                      "map coordinates; a relative name is read relative "
                      "to the .prm file.");
    if (dim == 3)
      {
        prm.declare_entry("Release depth",
                          "",
                          Patterns::Anything(),
                          "Type = polygon in 3D: how deep the material "
                          "stands over the footprint, measured vertically "
                          "from the ground: a depth in m, or a raster of "
                          "depths in m (an ESRI ASCII grid, or with GDAL "
                          "any raster it reads, e.g. GeoTIFF; a relative "
                          "name is read relative to the first .prm file's folder; nothing "
                          "is released outside its extent or at its NODATA "
                          "nodes).");
        prm.declare_entry("Release top surface",
                          "",
                          Patterns::FileName(),
                          "Type = polygon in 3D, instead of 'Release depth': "
                          "a raster (as 'Release depth') of the elevation (m) of the "
                          "released body's top: the material fills the "
                          "footprint from the mesh's ground up to it (the "
                          "pre-failure terrain over a bed with the failure "
                          "surface cut in).");
      }
  }


  void
  ReleaseArea::parse_parameters(ParameterHandler  &prm,
                                const unsigned int dim,
                                const std::string &path,
                                const std::string &input_directory)
  {
    rings.clear();
    const std::string file = prm.get("Polygon file");
    if (!file.empty())
      {
        const std::string name = resolve_path(input_directory, file);
        std::string extension = std::filesystem::path(name).extension().string();
        std::transform(extension.begin(),
                       extension.end(),
                       extension.begin(),
                       [](unsigned char c) { return std::tolower(c); });
        if (extension == ".geojson" || extension == ".json")
          rings = read_geojson(name);
        else
          {
            check_input(ElevationModel::gdal_available(),
                        path + "Polygon file = '" + file +
                          "': not GeoJSON (.geojson, .json), and this build "
                          "reads other formats only through GDAL, which it "
                          "was built without. Convert it ('ogr2ogr -f "
                          "GeoJSON out.geojson " + file +
                          "') or install GDAL (Debian: libgdal-dev) and "
                          "configure the build again.");
            rings = read_with_gdal(name);
          }
      }
    else
      {
        rings.emplace_back();
        for (const auto &v : Utilities::split_string_list(prm.get("Polygon"), ';'))
          rings.back().push_back(parse_point<2>(v, path + "Polygon"));
        check_input(rings.back().size() >= 3,
                    path + "Polygon needs at least three vertices.");
      }
    if (dim != 3)
      return;

    const std::string depth_text = Utilities::trim(prm.get("Release depth"));
    const std::string top_file   = prm.get("Release top surface");
    check_input(depth_text.empty() != top_file.empty(),
                path + "Type = polygon in 3D: give either 'Release depth' "
                       "(m, or a raster of depths) or 'Release top surface' "
                       "(a raster of the top's elevation); " +
                  std::string(depth_text.empty() ? "neither is given." :
                                                   "both are given."));
    if (!top_file.empty())
      {
        top_surface = std::make_shared<ElevationModel>();
        top_surface->read(resolve_path(input_directory, top_file));
        return;
      }
    try
      {
        std::size_t used = 0;
        depth            = std::stod(depth_text, &used);
        if (used != depth_text.size())
          throw std::invalid_argument(depth_text);
        check_input(depth > 0,
                    path + "Release depth = " + depth_text +
                      ": the depth must be positive.");
      }
    catch (const std::invalid_argument &)
      {
        depth_raster = std::make_shared<ElevationModel>();
        depth_raster->read(resolve_path(input_directory, depth_text));
      }
  }


  namespace
  {
    /// Whether a ray from (x, y) in +x crosses @p ring an odd number of
    /// times (the even-odd rule for one ring).
    bool
    odd_crossings(const std::vector<Point<2>> &ring, const double x, const double y)
    {
      bool odd = false;
      for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        {
          const Point<2> &a = ring[i], &b = ring[j];
          if ((a[1] > y) != (b[1] > y) &&
              x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0])
            odd = !odd;
        }
      return odd;
    }
  } // namespace


  bool
  ReleaseArea::footprint_contains(const double x, const double y) const
  {
    bool inside = false;
    for (const auto &ring : rings)
      inside = inside != odd_crossings(ring, x, y);
    return inside;
  }


  template <int dim>
  bool
  ReleaseArea::contains(const Point<dim> &x, const double h) const
  {
    if (!footprint_contains(x[0], x[1]))
      return false;
    if constexpr (dim == 3)
      {
        // NaN (a NODATA node nearby) compares false: nothing released.
        if (top_surface)
          return top_surface->covers(x[0], x[1]) &&
                 x[2] < top_surface->elevation(x[0], x[1]);
        if (depth_raster)
          return depth_raster->covers(x[0], x[1]) &&
                 h < depth_raster->elevation(x[0], x[1]);
        return h < depth;
      }
    else
      (void)h;
    return true;
  }


  std::array<double, 4>
  ReleaseArea::footprint_bounds() const
  {
    std::array<double, 4> bounds = {
      {rings[0][0][0], rings[0][0][1], rings[0][0][0], rings[0][0][1]}};
    for (const auto &ring : rings)
      for (const auto &v : ring)
        {
          bounds[0] = std::min(bounds[0], v[0]);
          bounds[1] = std::min(bounds[1], v[1]);
          bounds[2] = std::max(bounds[2], v[0]);
          bounds[3] = std::max(bounds[3], v[1]);
        }
    return bounds;
  }


  double
  ReleaseArea::footprint_area() const
  {
    // Shoelace per ring; under the even-odd rule a ring inside an odd
    // number of others is a hole.
    double area = 0;
    for (std::size_t r = 0; r < rings.size(); ++r)
      {
        double twice = 0;
        for (std::size_t i = 0; i < rings[r].size(); ++i)
          {
            const auto &a = rings[r][i];
            const auto &b = rings[r][(i + 1) % rings[r].size()];
            twice += a[0] * b[1] - b[0] * a[1];
          }
        unsigned int depth_of_nesting = 0;
        for (std::size_t o = 0; o < rings.size(); ++o)
          if (o != r)
            depth_of_nesting +=
              odd_crossings(rings[o], rings[r][0][0], rings[r][0][1]);
        area += (depth_of_nesting % 2 == 0 ? 0.5 : -0.5) * std::abs(twice);
      }
    return area;
  }


  std::vector<std::vector<Point<2>>>
  ReleaseArea::read_geojson(const std::string &file)
  {
    namespace pt = boost::property_tree;
    check_input(static_cast<bool>(std::ifstream(file)),
                "Cannot open the polygon file '" + file + "'.");
    pt::ptree root;
    try
      {
        pt::read_json(file, root);
      }
    catch (const pt::json_parser_error &e)
      {
        throw InputError("Polygon file '" + file + "', line " +
                         std::to_string(e.line()) + ": not valid JSON (" +
                         e.message() + ").");
      }
    std::vector<std::vector<Point<2>>> rings;
    // A ring: an array of positions [x, y] or [x, y, z].
    const auto read_ring = [&](const pt::ptree &ring) {
      std::vector<Point<2>> points;
      for (const auto &position : ring)
        {
          std::vector<double> xy;
          for (const auto &c : position.second)
            {
              const auto value = c.second.get_value_optional<double>();
              check_input(static_cast<bool>(value),
                          "Polygon file '" + file + "': the coordinate '" +
                            c.second.data() + "' is not a number.");
              xy.push_back(*value);
            }
          check_input(xy.size() >= 2,
                      "Polygon file '" + file +
                        "': a position with fewer than two coordinates.");
          points.emplace_back(xy[0], xy[1]);
        }
      // GeoJSON closes a ring by repeating its first position.
      if (points.size() > 1 && points.front() == points.back())
        points.pop_back();
      check_input(points.size() >= 3,
                  "Polygon file '" + file +
                    "': a ring with fewer than three positions.");
      rings.push_back(points);
    };
    const auto read_geometry = [&](const pt::ptree &geometry) {
      const std::string type = geometry.get<std::string>("type", "");
      const auto coordinates = geometry.get_child_optional("coordinates");
      if (!coordinates)
        return;
      if (type == "Polygon")
        for (const auto &ring : *coordinates)
          read_ring(ring.second);
      else if (type == "MultiPolygon")
        for (const auto &polygon : *coordinates)
          for (const auto &ring : polygon.second)
            read_ring(ring.second);
    };
    const std::string type = root.get<std::string>("type", "");
    if (type == "FeatureCollection")
      {
        if (const auto features = root.get_child_optional("features"))
          for (const auto &feature : *features)
            if (const auto geometry =
                  feature.second.get_child_optional("geometry"))
              read_geometry(*geometry);
      }
    else if (type == "Feature")
      {
        if (const auto geometry = root.get_child_optional("geometry"))
          read_geometry(*geometry);
      }
    else
      read_geometry(root);
    check_input(!rings.empty(),
                "Polygon file '" + file +
                  "' holds no Polygon or MultiPolygon geometry.");
    return rings;
  }


  template bool
  ReleaseArea::contains(const Point<2> &, const double) const;
  template bool
  ReleaseArea::contains(const Point<3> &, const double) const;
} // namespace MPM
