// Release polygons through GDAL/OGR: compiled with GDAL when the build
// found it (MPM_WITH_GDAL), else a function that says it is missing.
#include <mpm/base/input_error.h>
#include <mpm/material_points/release_area.h>

#ifdef MPM_WITH_GDAL
#  include <cpl_error.h>
#  include <gdal.h>
#  include <ogr_api.h>
#endif

#include <memory>

namespace MPM
{
#ifdef MPM_WITH_GDAL
  namespace
  {
    /// The rings of a polygon or multipolygon (and of any collection).
    void
    add_rings(OGRGeometryH geometry, std::vector<std::vector<Point<2>>> &rings)
    {
      const OGRwkbGeometryType type =
        wkbFlatten(OGR_G_GetGeometryType(geometry));
      if (type == wkbLinearRing || type == wkbLineString)
        {
          std::vector<Point<2>> ring;
          for (int i = 0; i < OGR_G_GetPointCount(geometry); ++i)
            ring.emplace_back(OGR_G_GetX(geometry, i), OGR_G_GetY(geometry, i));
          if (ring.size() > 1 && ring.front() == ring.back())
            ring.pop_back();
          if (ring.size() >= 3)
            rings.push_back(ring);
          return;
        }
      if (type == wkbPolygon || type == wkbMultiPolygon ||
          type == wkbGeometryCollection)
        for (int g = 0; g < OGR_G_GetGeometryCount(geometry); ++g)
          add_rings(OGR_G_GetGeometryRef(geometry, g), rings);
    }
  } // namespace


  std::vector<std::vector<Point<2>>>
  ReleaseArea::read_with_gdal(const std::string &file)
  {
    GDALAllRegister();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
    const GDALDatasetH dataset =
      GDALOpenEx(file.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr);
    CPLPopErrorHandler();
    check_input(dataset != nullptr,
                "Polygon file '" + file + "': GDAL cannot open it (" +
                  CPLGetLastErrorMsg() + ").");
    const std::unique_ptr<void, void (*)(GDALDatasetH)> closer(dataset, GDALClose);
    std::vector<std::vector<Point<2>>> rings;
    for (int l = 0; l < GDALDatasetGetLayerCount(dataset); ++l)
      {
        const OGRLayerH layer = GDALDatasetGetLayer(dataset, l);
        OGR_L_ResetReading(layer);
        while (OGRFeatureH feature = OGR_L_GetNextFeature(layer))
          {
            if (OGRGeometryH geometry = OGR_F_GetGeometryRef(feature))
              {
                const OGRwkbGeometryType type =
                  wkbFlatten(OGR_G_GetGeometryType(geometry));
                if (type == wkbPolygon || type == wkbMultiPolygon ||
                    type == wkbGeometryCollection)
                  add_rings(geometry, rings);
              }
            OGR_F_Destroy(feature);
          }
      }
    check_input(!rings.empty(),
                "Polygon file '" + file + "' holds no polygon.");
    return rings;
  }
#else
  std::vector<std::vector<Point<2>>>
  ReleaseArea::read_with_gdal(const std::string &file)
  {
    throw InputError("Polygon file '" + file +
                     "': this build has no GDAL (install libgdal-dev and "
                     "configure the build again), or convert it to GeoJSON.");
  }
#endif
} // namespace MPM
