#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <mpm/base/input_deck.h>
#include <mpm/base/input_error.h>
#include <mpm/grid/terrain.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace MPM
{
  void
  ElevationModel::read_esri_ascii(const std::string &file)
  {
    std::ifstream in(file);
    check_input(static_cast<bool>(in),
                "Cannot open the elevation model '" + file + "'.");
    // The header: keyword value lines, case-insensitive, until the first
    // line that starts with a number.
    std::map<std::string, double> header;
    std::string                   line;
    unsigned int                  line_number = 0;
    std::streampos                data_start  = in.tellg();
    while (std::getline(in, line))
      {
        ++line_number;
        std::istringstream words(line);
        std::string        key;
        if (!(words >> key))
          {
            data_start = in.tellg();
            continue;
          }
        if (std::isdigit(static_cast<unsigned char>(key[0])) || key[0] == '-' ||
            key[0] == '+' || key[0] == '.')
          break;
        std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) {
          return std::tolower(c);
        });
        double value = 0;
        check_input(static_cast<bool>(words >> value),
                    "Elevation model '" + file + "', line " +
                      std::to_string(line_number) + ": header entry '" + key +
                      "' has no numeric value.");
        header[key] = value;
        data_start  = in.tellg();
      }
    for (const std::string key : {"ncols", "nrows", "cellsize"})
      check_input(header.count(key) == 1,
                  "Elevation model '" + file + "': the ESRI ASCII header has "
                  "no '" + key + "'.");
    const bool centre = header.count("xllcenter") == 1;
    check_input((centre && header.count("yllcenter") == 1) ||
                  (header.count("xllcorner") == 1 &&
                   header.count("yllcorner") == 1),
                "Elevation model '" + file + "': the header needs xllcorner "
                "and yllcorner (or xllcenter and yllcenter).");
    const double ncols = header["ncols"], nrows = header["nrows"];
    check_input(ncols >= 2 && nrows >= 2 && ncols == std::floor(ncols) &&
                  nrows == std::floor(nrows) && ncols * nrows < 1e9,
                "Elevation model '" + file + "': ncols and nrows must be "
                "integers of at least 2.");
    spacing = header["cellsize"];
    check_input(spacing > 0,
                "Elevation model '" + file + "': cellsize must be positive.");
    n_x = static_cast<unsigned int>(ncols);
    n_y = static_cast<unsigned int>(nrows);
    // Nodes at the cell centres.
    x0 = centre ? header["xllcenter"] : header["xllcorner"] + 0.5 * spacing;
    y0 = centre ? header["yllcenter"] : header["yllcorner"] + 0.5 * spacing;
    const bool   has_nodata = header.count("nodata_value") == 1;
    const double nodata     = has_nodata ? header["nodata_value"] : 0;

    in.clear();
    in.seekg(data_start);
    z.assign(std::size_t(n_x) * n_y, 0.);
    std::string word;
    for (unsigned int row = 0; row < n_y; ++row)
      for (unsigned int i = 0; i < n_x; ++i)
        {
          check_input(static_cast<bool>(in >> word),
                      "Elevation model '" + file + "': " +
                        std::to_string(std::size_t(n_x) * n_y) +
                        " elevations expected (ncols x nrows), the file "
                        "ends after " +
                        std::to_string(std::size_t(row) * n_x + i) + ".");
          double value = 0;
          try
            {
              std::size_t used = 0;
              value            = std::stod(word, &used);
              if (used != word.size())
                throw std::invalid_argument(word);
            }
          catch (const std::exception &)
            {
              throw InputError("Elevation model '" + file + "': '" + word +
                               "' (row " + std::to_string(row + 1) +
                               ", column " + std::to_string(i + 1) +
                               ") is not a number.");
            }
          if (has_nodata && value == nodata)
            value = std::numeric_limits<double>::quiet_NaN();
          // Rows run from the north: row 0 is j = n_y - 1.
          z[std::size_t(n_y - 1 - row) * n_x + i] = value;
        }
    check_input(!(in >> word),
                "Elevation model '" + file + "': more values than ncols x "
                "nrows = " + std::to_string(std::size_t(n_x) * n_y) + ".");
    file_name            = file;
    header_at_centre     = centre;
    first_column         = 0;
    first_row_from_south = 0;
    file_rows            = n_y;
  }


  void
  ElevationModel::read(const std::string &file)
  {
    std::string extension = std::filesystem::path(file).extension().string();
    std::transform(extension.begin(),
                   extension.end(),
                   extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (extension == ".asc")
      {
        read_esri_ascii(file);
        // An ESRI ASCII grid keeps its coordinate system beside it.
        std::ifstream prj(std::filesystem::path(file).replace_extension(".prj"));
        if (prj)
          projection_wkt.assign(std::istreambuf_iterator<char>(prj),
                                std::istreambuf_iterator<char>());
        return;
      }
    check_input(gdal_available(),
                "Raster '" + file + "': not an ESRI ASCII grid (.asc), and "
                "this build reads other formats only through GDAL, which it "
                "was built without. Convert it ('gdal_translate -of AAIGrid " +
                  file + " out.asc'), or install GDAL (Debian: libgdal-dev) "
                  "and configure the build again.");
    read_with_gdal(file);
  }


  void
  ElevationModel::write_esri_ascii(const std::string &file) const
  {
    std::ofstream out(file + ".new");
    out << std::setprecision(12) << "ncols " << n_x << "\nnrows " << n_y
        << '\n';
    if (header_at_centre)
      out << "xllcenter " << x0 << "\nyllcenter " << y0 << '\n';
    else
      out << "xllcorner " << x0 - 0.5 * spacing << "\nyllcorner "
          << y0 - 0.5 * spacing << '\n';
    out << "cellsize " << spacing << "\nNODATA_value -9999\n"
        << std::setprecision(9);
    for (unsigned int j = n_y; j-- > 0;)
      {
        for (unsigned int i = 0; i < n_x; ++i)
          {
            const double value = z[std::size_t(j) * n_x + i];
            out << (i > 0 ? " " : "");
            if (std::isnan(value))
              out << "-9999";
            else
              out << value;
          }
        out << '\n';
      }
    out.close();
    AssertThrow(out, ExcMessage("Could not write " + file + ".new"));
    std::filesystem::rename(file + ".new", file);
  }


  void
  ElevationModel::crop(const double       x_min,
                       const double       y_min,
                       const double       x_max,
                       const double       y_max,
                       const std::string &parameter)
  {
    // Nodes on the rectangle's edge count as inside it, up to round-off
    // in the header's coordinates.
    const double tolerance = 1e-6 * spacing;
    const auto   first     = [&](const double lower, const double origin) {
      return static_cast<long>(std::ceil((lower - origin - tolerance) / spacing));
    };
    const auto last = [&](const double upper, const double origin) {
      return static_cast<long>(std::floor((upper - origin + tolerance) / spacing));
    };
    const long i_begin = std::max(0L, first(x_min, x0));
    const long i_end   = std::min<long>(n_x - 1, last(x_max, x0));
    const long j_begin = std::max(0L, first(y_min, y0));
    const long j_end   = std::min<long>(n_y - 1, last(y_max, y0));
    check_input(i_end - i_begin >= 1 && j_end - j_begin >= 1,
                parameter + ": the rectangle holds fewer than 2 x 2 nodes of "
                "the elevation model '" + file_name + "' (nodes at x = " +
                  Utilities::to_string(x0) + " ... " +
                  Utilities::to_string(node_x(n_x - 1)) + ", y = " +
                  Utilities::to_string(y0) + " ... " +
                  Utilities::to_string(node_y(n_y - 1)) + ", spacing " +
                  Utilities::to_string(spacing) + ").");
    const unsigned int  new_n_x = i_end - i_begin + 1;
    const unsigned int  new_n_y = j_end - j_begin + 1;
    std::vector<double> cropped(std::size_t(new_n_x) * new_n_y);
    for (unsigned int j = 0; j < new_n_y; ++j)
      for (unsigned int i = 0; i < new_n_x; ++i)
        cropped[std::size_t(j) * new_n_x + i] =
          z[std::size_t(j + j_begin) * n_x + i + i_begin];
    x0 = node_x(i_begin);
    y0 = node_y(j_begin);
    first_column += i_begin;
    first_row_from_south += j_begin;
    n_x = new_n_x;
    n_y = new_n_y;
    z.swap(cropped);
  }


  void
  ElevationModel::check_complete() const
  {
    // Row by row as the file holds them, from the north.
    for (unsigned int jj = n_y; jj-- > 0;)
      for (unsigned int i = 0; i < n_x; ++i)
        if (std::isnan(z[std::size_t(jj) * n_x + i]))
          throw InputError(
            "Elevation model '" + file_name + "': row " +
            std::to_string(file_rows - first_row_from_south - jj) +
            ", column " + std::to_string(first_column + i + 1) + " (x = " +
            Utilities::to_string(node_x(i)) + ", y = " +
            Utilities::to_string(node_y(jj)) +
            ") holds the NODATA value; the mesh needs the ground "
            "everywhere in the grid (fill the DEM, or crop it with "
            "'Mesh/Terrain/Area of interest').");
  }


  double
  ElevationModel::elevation(const double x, const double y) const
  {
    const double s  = std::clamp((x - x0) / spacing, 0., n_x - 1.);
    const double t  = std::clamp((y - y0) / spacing, 0., n_y - 1.);
    const auto   i  = std::min<unsigned int>(n_x - 2, static_cast<unsigned int>(s));
    const auto   j  = std::min<unsigned int>(n_y - 2, static_cast<unsigned int>(t));
    const double fs = s - i, ft = t - j;
    const auto   at = [&](const unsigned int a, const unsigned int b) {
      return z[std::size_t(b) * n_x + a];
    };
    return (1 - fs) * (1 - ft) * at(i, j) + fs * (1 - ft) * at(i + 1, j) +
           (1 - fs) * ft * at(i, j + 1) + fs * ft * at(i + 1, j + 1);
  }


  void
  TerrainMesh::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Terrain");
    prm.declare_entry("Elevation model",
                      "",
                      Patterns::FileName(),
                      "The ground elevation (m): an ESRI ASCII grid (.asc), "
                      "or with GDAL any raster it reads (GeoTIFF: .tif); "
                      "a relative name is read relative to the first .prm file's folder. "
                      "Mesh/Source = terrain builds the mesh on it (3D).");
    prm.declare_entry("Area of interest",
                      "",
                      Patterns::Anything(),
                      "Mesh only the part of the elevation model within "
                      "the rectangle 'x_min, y_min : x_max, y_max' (map "
                      "coordinates, m; nodes on its edge kept); empty: the "
                      "whole grid. NODATA outside it is allowed, inside it "
                      "an input error.");
    prm.declare_entry("Section line",
                      "",
                      Patterns::Anything(),
                      "2D only: the line 'x0, y0 : x1, y1' (map coordinates, "
                      "m) through the elevation model along which the 2D "
                      "mesh follows the ground; the mesh's x is the "
                      "distance from (x0, y0), its y the elevation.");
    prm.declare_entry("Node stride",
                      "1",
                      Patterns::Integer(1),
                      "Mesh vertices on every k-th node of the elevation "
                      "grid in x and y (the cell size is k times the grid "
                      "spacing; (ncols - 1) and (nrows - 1) must be "
                      "multiples of k).");
    prm.declare_entry("Height above ground",
                      "1",
                      Patterns::Double(0),
                      "Thickness (m) of the meshed layer over the ground, "
                      "measured vertically: material must stay below it.");
    prm.declare_entry("Layers",
                      "4",
                      Patterns::Integer(1),
                      "Number of cells across that thickness (terrain-"
                      "following layers).");
    prm.leave_subsection();
  }


  void
  TerrainMesh::parse_parameters(ParameterHandler  &prm,
                                const std::string &input_directory)
  {
    prm.enter_subsection("Terrain");
    dem_file = resolve_path(input_directory, prm.get("Elevation model"));
    stride   = prm.get_integer("Node stride");
    height   = prm.get_double("Height above ground");
    layers   = prm.get_integer("Layers");
    const std::string area = Utilities::trim(prm.get("Area of interest"));
    const std::string line = Utilities::trim(prm.get("Section line"));
    prm.leave_subsection();
    section = {{0, 0, 0, 0}};
    if (!line.empty())
      {
        std::vector<double> values;
        for (const auto &end : Utilities::split_string_list(line, ':'))
          try
            {
              const auto xy =
                Utilities::string_to_double(Utilities::split_string_list(end));
              values.insert(values.end(), xy.begin(), xy.end());
            }
          catch (const std::exception &)
            {
              values.clear();
              break;
            }
        check_input(values.size() == 4,
                    "Mesh/Terrain/Section line = '" + line +
                      "': give 'x0, y0 : x1, y1'.");
        std::copy(values.begin(), values.end(), section.begin());
      }
    area_of_interest.clear();
    if (!area.empty())
      {
        const auto corners = Utilities::split_string_list(area, ':');
        bool       valid   = corners.size() == 2;
        for (const auto &corner : corners)
          {
            try
              {
                const auto xy = Utilities::string_to_double(
                  Utilities::split_string_list(corner));
                valid = valid && xy.size() == 2;
                area_of_interest.insert(area_of_interest.end(), xy.begin(), xy.end());
              }
            catch (const std::exception &)
              {
                valid = false;
              }
          }
        check_input(valid && area_of_interest.size() == 4 &&
                      area_of_interest[0] < area_of_interest[2] &&
                      area_of_interest[1] < area_of_interest[3],
                    "Mesh/Terrain/Area of interest = '" + area +
                      "': give 'x_min, y_min : x_max, y_max' with x_min < "
                      "x_max and y_min < y_max.");
      }
    check_input(height > 0,
                "Mesh/Terrain/Height above ground must be positive.");
  }


  namespace
  {
    /// The elevation model of a terrain mesh, cropped to the area of
    /// interest if one is given (both dimensions).
    void
    read_elevation_model(const std::string         &file,
                         const std::vector<double> &area_of_interest,
                         ElevationModel            &dem)
    {
      check_input(!file.empty(),
                  "Mesh/Source = terrain, but 'Mesh/Terrain/Elevation "
                  "model' is empty.");
      dem.read(file);
      if (!area_of_interest.empty())
        dem.crop(area_of_interest[0],
                 area_of_interest[1],
                 area_of_interest[2],
                 area_of_interest[3],
                 "Mesh/Terrain/Area of interest");
    }
  } // namespace


  void
  TerrainMesh::create(Triangulation<2> &triangulation)
  {
    read_elevation_model(dem_file, area_of_interest, dem);
    const double length = section_length();
    for (unsigned int e = 0; e < 2; ++e)
      check_input(dem.covers(section[2 * e], section[2 * e + 1]),
                  "Mesh/Terrain/Section line: the point (" +
                    Utilities::to_string(section[2 * e]) + ", " +
                    Utilities::to_string(section[2 * e + 1]) +
                    ") lies outside the elevation model '" + dem_file + "'.");
    // Cells of about 'Node stride' DEM spacings along the line.
    const unsigned int n_cells = std::max<unsigned int>(
      1, static_cast<unsigned int>(std::round(length / (stride * dem.spacing))));
    profile.clear();
    std::vector<double> ground(n_cells + 1);
    for (unsigned int k = 0; k <= n_cells; ++k)
      {
        const double s = length * k / n_cells;
        ground[k]      = section_elevation(s);
        check_input(std::isfinite(ground[k]),
                    "Elevation model '" + dem_file +
                      "': the section line meets a NODATA node at " +
                      Utilities::to_string(s) +
                      " m from its start; the mesh needs the ground there.");
      }
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              {n_cells, layers},
                                              Point<2>(0., 0.),
                                              Point<2>(length, 1.),
                                              true);
    GridTools::transform(
      [&](const Point<2> &p) {
        const unsigned int k = static_cast<unsigned int>(
          std::round(p[0] / length * n_cells));
        return Point<2>(p[0], ground[k] + p[1] * height);
      },
      triangulation);
    profile = ground;
  }


  void
  TerrainMesh::create(Triangulation<3> &triangulation)
  {
    read_elevation_model(dem_file, area_of_interest, dem);
    dem.check_complete();
    const ElevationModel &model = dem;
    check_input((model.n_x - 1) % stride == 0 && (model.n_y - 1) % stride == 0,
                "Mesh/Terrain/Node stride = " + std::to_string(stride) +
                  " must divide ncols - 1 = " + std::to_string(model.n_x - 1) +
                  " and nrows - 1 = " + std::to_string(model.n_y - 1) +
                  " of '" + dem_file + "'.");
    const std::vector<unsigned int> repetitions = {(model.n_x - 1) / stride,
                                                   (model.n_y - 1) / stride,
                                                   layers};
    const Point<3> lower(model.x0, model.y0, 0.);
    const Point<3> upper(model.x0 + (model.n_x - 1) * model.spacing,
                         model.y0 + (model.n_y - 1) * model.spacing,
                         1.);
    GridGenerator::subdivided_hyper_rectangle(
      triangulation, repetitions, lower, upper, true);
    // The unit thickness becomes the terrain-following layer: the vertices
    // of each vertical line sit on DEM nodes, so the ground is the DEM
    // (piecewise bilinear over each cell's bottom face).
    GridTools::transform(
      [&](const Point<3> &p) {
        return Point<3>(p[0], p[1], model.elevation(p[0], p[1]) + p[2] * height);
      },
      triangulation);
  }
} // namespace MPM
