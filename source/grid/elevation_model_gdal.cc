// The ElevationModel's GDAL input and output: compiled with GDAL when the
// build found it (MPM_WITH_GDAL), else functions that say it is missing.
#include <mpm/base/input_error.h>
#include <mpm/grid/terrain.h>

#ifdef MPM_WITH_GDAL
#  include <cpl_error.h>
#  include <gdal.h>
#endif

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

namespace MPM
{
  bool
  ElevationModel::gdal_available()
  {
#ifdef MPM_WITH_GDAL
    return true;
#else
    return false;
#endif
  }


#ifdef MPM_WITH_GDAL
  void
  ElevationModel::read_with_gdal(const std::string &file)
  {
    GDALAllRegister();
    // GDAL's message goes into the InputError, not to stderr as well.
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
    const GDALDatasetH dataset = GDALOpen(file.c_str(), GA_ReadOnly);
    CPLPopErrorHandler();
    check_input(dataset != nullptr,
                "Raster '" + file + "': GDAL cannot open it (" +
                  CPLGetLastErrorMsg() + ").");
    // One owner of the dataset, closed on every way out.
    const std::unique_ptr<void, void (*)(GDALDatasetH)> closer(dataset, GDALClose);
    double transform[6];
    check_input(GDALGetGeoTransform(dataset, transform) == CE_None,
                "Raster '" + file + "' has no georeferencing (geotransform).");
    check_input(transform[2] == 0 && transform[4] == 0 &&
                  transform[1] > 0 && transform[5] < 0,
                "Raster '" + file + "' is not north-up (its geotransform "
                "rotates or flips the grid): warp it first, e.g. "
                "'gdalwarp " + file + " out.tif'.");
    check_input(std::abs(transform[1] + transform[5]) <= 1e-9 * transform[1],
                "Raster '" + file + "': its cells are not square (" +
                  std::to_string(transform[1]) + " x " +
                  std::to_string(-transform[5]) +
                  " m); resample it, e.g. 'gdalwarp -tr 1 1 " + file +
                  " out.tif'.");
    n_x = GDALGetRasterXSize(dataset);
    n_y = GDALGetRasterYSize(dataset);
    check_input(n_x >= 2 && n_y >= 2,
                "Raster '" + file + "' needs at least 2 x 2 cells.");
    spacing = transform[1];
    // Values at cell centres; row 0 is the northernmost.
    x0 = transform[0] + 0.5 * spacing;
    y0 = transform[3] - (n_y - 0.5) * spacing;
    const GDALRasterBandH band = GDALGetRasterBand(dataset, 1);
    std::vector<double>   rows(std::size_t(n_x) * n_y);
    check_input(GDALRasterIO(band,
                             GF_Read,
                             0,
                             0,
                             n_x,
                             n_y,
                             rows.data(),
                             n_x,
                             n_y,
                             GDT_Float64,
                             0,
                             0) == CE_None,
                "Raster '" + file + "': GDAL cannot read band 1 (" +
                  CPLGetLastErrorMsg() + ").");
    int          has_nodata = 0;
    const double nodata     = GDALGetRasterNoDataValue(band, &has_nodata);
    z.assign(rows.size(), 0.);
    for (unsigned int row = 0; row < n_y; ++row)
      for (unsigned int i = 0; i < n_x; ++i)
        {
          const double value = rows[std::size_t(row) * n_x + i];
          z[std::size_t(n_y - 1 - row) * n_x + i] =
            (has_nodata && value == nodata) ?
              std::numeric_limits<double>::quiet_NaN() :
              value;
        }
    const char *wkt      = GDALGetProjectionRef(dataset);
    projection_wkt       = wkt != nullptr ? wkt : "";
    file_name            = file;
    header_at_centre     = false;
    first_column         = 0;
    first_row_from_south = 0;
    file_rows            = n_y;
  }


  void
  ElevationModel::write_geotiff(const std::string &file) const
  {
    GDALAllRegister();
    const GDALDriverH driver = GDALGetDriverByName("GTiff");
    AssertThrow(driver != nullptr, ExcMessage("GDAL has no GTiff driver."));
    const std::string temporary = file + ".new";
    char             *options[] = {const_cast<char *>("COMPRESS=DEFLATE"), nullptr};
    const GDALDatasetH dataset  = GDALCreate(
      driver, temporary.c_str(), n_x, n_y, 1, GDT_Float64, options);
    AssertThrow(dataset != nullptr,
                ExcMessage("GDAL cannot create " + temporary + ": " +
                           CPLGetLastErrorMsg()));
    double transform[6] = {x0 - 0.5 * spacing,
                           spacing,
                           0,
                           y0 + (n_y - 0.5) * spacing,
                           0,
                           -spacing};
    GDALSetGeoTransform(dataset, transform);
    if (!projection_wkt.empty())
      GDALSetProjection(dataset, projection_wkt.c_str());
    const GDALRasterBandH band = GDALGetRasterBand(dataset, 1);
    GDALSetRasterNoDataValue(band, -9999);
    std::vector<double> rows(z.size());
    for (unsigned int row = 0; row < n_y; ++row)
      for (unsigned int i = 0; i < n_x; ++i)
        {
          const double value = z[std::size_t(n_y - 1 - row) * n_x + i];
          rows[std::size_t(row) * n_x + i] = std::isnan(value) ? -9999. : value;
        }
    const CPLErr written = GDALRasterIO(
      band, GF_Write, 0, 0, n_x, n_y, rows.data(), n_x, n_y, GDT_Float64, 0, 0);
    GDALClose(dataset);
    AssertThrow(written == CE_None,
                ExcMessage("GDAL cannot write " + temporary));
    std::filesystem::rename(temporary, file);
  }
#else
  void
  ElevationModel::read_with_gdal(const std::string &file)
  {
    throw InputError("Raster '" + file +
                     "': this build has no GDAL (install libgdal-dev "
                     "and configure the build again).");
  }


  void
  ElevationModel::write_geotiff(const std::string &file) const
  {
    throw InputError("Cannot write '" + file +
                     "' as GeoTIFF: this build has no GDAL (install "
                     "libgdal-dev and configure the build again), or "
                     "write ESRI ASCII grids.");
  }
#endif
} // namespace MPM
