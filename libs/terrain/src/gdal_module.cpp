// The GDAL module: band 1 of any raster GDAL opens, and GDAL's no-data fill. Built as a
// module so that programs load GDAL's ~110 shared libraries only when they read a raster
// through it (~85 ms at every start otherwise). Errors go back as messages.
#include "gdal_module.h"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <new>

namespace {

using shanshui::terrain::detail::GdalRaster;
using shanshui::terrain::detail::GdalReader;

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};

// GDAL's errors stay quiet; the last message is the one reported.
struct QuietGdal {
  QuietGdal() {
    static std::once_flag registered;
    std::call_once(registered, [] { GDALAllRegister(); });
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdal() { CPLPopErrorHandler(); }
  static std::string message(const char* fallback) {
    const std::string m = CPLGetLastErrorMsg();
    return m.empty() ? fallback : m;
  }
};

std::string readRaster(const std::string& path, std::size_t max_samples, std::size_t cap, GdalRaster* out) try {
  QuietGdal quiet;
  std::unique_ptr<GDALDataset, DatasetCloser> ds(
      GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR));
  if (!ds) return "not a raster GDAL can read (" + QuietGdal::message("unknown format") + ")";
  GdalRaster& r = *out;
  r.source_columns = ds->GetRasterXSize();
  r.source_rows = ds->GetRasterYSize();
  r.bands = ds->GetRasterCount();
  if (r.bands < 1 || r.source_columns < 1 || r.source_rows < 1) return "has no raster band";
  for (int b = 1; b <= r.bands; ++b) r.colour_bands += ds->GetRasterBand(b)->GetColorInterpretation() != GCI_AlphaBand;
  GDALRasterBand* band = ds->GetRasterBand(1);
  r.driver = ds->GetDriver() ? ds->GetDriver()->GetDescription() : "GDAL";
  r.type = GDALGetDataTypeName(band->GetRasterDataType());
  r.georeferenced = ds->GetGeoTransform(r.geotransform) == CE_None;
  if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
    if (srs->IsGeographic()) {
      r.crs = GdalRaster::Crs::Geographic;
      r.crs_unit = srs->GetAngularUnits() * 180.0 / M_PI;
    } else if (srs->IsProjected()) {
      r.crs = GdalRaster::Crs::Projected;
      r.crs_unit = srs->GetLinearUnits();
    } else {
      r.crs = GdalRaster::Crs::Other;
    }
    if (srs->IsCompound()) {
      const char* name = nullptr;
      r.z_unit_metres = srs->GetTargetLinearUnits("VERT_CS", &name);
      r.z_unit = name ? name : "";
    }
  }
  if (const char* unit = band->GetUnitType(); unit && *unit) {
    r.z_unit = unit;
    r.z_unit_metres = 0.0;
  }

  // The smallest whole factor that brings the grid within max_samples.
  const double samples = static_cast<double>(r.source_columns) * r.source_rows;
  auto within = [&](int f) {
    return static_cast<double>((r.source_columns + f - 1) / f) * ((r.source_rows + f - 1) / f) <=
           static_cast<double>(max_samples);
  };
  if (max_samples > 0 && samples > static_cast<double>(max_samples)) {
    r.factor = std::max(1, static_cast<int>(std::sqrt(samples / static_cast<double>(max_samples))));
    while (!within(r.factor)) ++r.factor;
  }
  r.columns = (r.source_columns + r.factor - 1) / r.factor;
  r.rows = (r.source_rows + r.factor - 1) / r.factor;
  const double keep = static_cast<double>(r.columns) * r.rows;
  if (keep > static_cast<double>(cap)) {
    return std::to_string(r.source_columns) + " x " + std::to_string(r.source_rows) + " samples would need " +
           std::to_string(keep * 8 / (1u << 30)) +
           " GiB, more than the limit or the memory budget (--max-memory) allows; give a vertex budget "
           "(--max-vertices) "
           "to read it decimated";
  }
  r.z.resize(static_cast<std::size_t>(keep));
  GDALRasterIOExtraArg extra;
  INIT_RASTERIO_EXTRA_ARG(extra);
  extra.eResampleAlg = r.factor > 1 ? GRIORA_Average : GRIORA_NearestNeighbour;
  if (band->RasterIO(GF_Read, 0, 0, r.source_columns, r.source_rows, r.z.data(), r.columns, r.rows, GDT_Float64, 0, 0,
                     &extra) != CE_None) {
    return "cannot read its samples (" + QuietGdal::message("read error") + "; truncated?)";
  }
  // No-data: the band's value, its mask (alpha, internal masks) and non-finite samples.
  int has = 0;
  r.no_data_value = band->GetNoDataValue(&has);
  r.has_no_data_value = has != 0;
  std::vector<unsigned char> mask;
  if (!(band->GetMaskFlags() & GMF_ALL_VALID)) {
    mask.resize(r.z.size());
    extra.eResampleAlg = GRIORA_NearestNeighbour;
    if (band->GetMaskBand()->RasterIO(GF_Read, 0, 0, r.source_columns, r.source_rows, mask.data(), r.columns, r.rows,
                                      GDT_Byte, 0, 0, &extra) != CE_None) {
      return "cannot read its no-data mask (" + QuietGdal::message("read error") + ")";
    }
  }
  int hasScale = 0, hasOffset = 0;
  const double scale = band->GetScale(&hasScale), offset = band->GetOffset(&hasOffset);
  r.scale = hasScale ? scale : 1.0;
  r.offset = hasOffset ? offset : 0.0;
  for (std::size_t i = 0; i < r.z.size(); ++i) {
    double& z = r.z[i];
    const bool isNoData =
        r.has_no_data_value && (z == r.no_data_value || (std::isnan(r.no_data_value) && std::isnan(z)));
    if (!std::isfinite(z) || isNoData || (!mask.empty() && mask[i] == 0)) {
      z = std::nan("");
      ++r.no_data;
    } else {
      z = z * r.scale + r.offset;
    }
  }
  return "";
} catch (const std::bad_alloc&) {
  return "out of memory reading it";
} catch (const std::exception& e) {
  return e.what();
}

std::string fillHoles(std::vector<double>* z, int columns, int rows) try {
  QuietGdal quiet;
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!mem) return "GDAL has no MEM driver";
  std::unique_ptr<GDALDataset, DatasetCloser> ds(mem->Create("", columns, rows, 2, GDT_Float64, nullptr));
  if (!ds) return "cannot make a grid to fill (" + QuietGdal::message("GDAL error") + ")";
  std::vector<double> valid(z->size());
  for (std::size_t i = 0; i < valid.size(); ++i) valid[i] = std::isnan((*z)[i]) ? 0.0 : 1.0;
  GDALRasterBand* band = ds->GetRasterBand(1);
  GDALRasterBand* mask = ds->GetRasterBand(2);
  if (band->RasterIO(GF_Write, 0, 0, columns, rows, z->data(), columns, rows, GDT_Float64, 0, 0) != CE_None ||
      mask->RasterIO(GF_Write, 0, 0, columns, rows, valid.data(), columns, rows, GDT_Float64, 0, 0) != CE_None ||
      GDALFillNodata(band, mask, std::max(columns, rows), 0, 0, nullptr, nullptr, nullptr) != CE_None ||
      band->RasterIO(GF_Read, 0, 0, columns, rows, z->data(), columns, rows, GDT_Float64, 0, 0) != CE_None) {
    return "filling no-data failed (" + QuietGdal::message("GDAL error") + ")";
  }
  return "";
} catch (const std::bad_alloc&) {
  return "out of memory filling no-data";
}

const GdalReader kReader{shanshui::terrain::detail::kGdalReaderAbi, readRaster, fillHoles};

}  // namespace

extern "C" __attribute__((visibility("default"))) const GdalReader* shanshui_gdal_reader() {
  return &kReader;
}
