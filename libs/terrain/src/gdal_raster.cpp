// Every raster DEM that GDAL opens (GeoTIFF of any sample type, COG, BigTIFF, SRTM .hgt,
// VRT mosaics, ERDAS .img, PNG and TIFF height maps, ...). GDAL itself is in a module
// (gdal_module.cpp) loaded on first use; here the samples it returns become metres: cell
// size and origin from the georeference, geographic grids projected at their centre
// latitude, vertical units converted, no-data left as NaN and reported.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "gdal_module.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/core/module.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::terrain {
namespace fs = std::filesystem;
namespace {

using detail::GdalRaster;
using detail::GdalReader;

constexpr const char* kModuleName = "libshanshui_terrain_gdal.so";

const GdalReader& gdalReader(const std::string& name) {
  static std::string error;
  static const GdalReader* reader = [] {
#ifdef SHANSHUI_TERRAIN_MODULE_DIR
    const std::string build_dir = SHANSHUI_TERRAIN_MODULE_DIR;
#else
    const std::string build_dir;
#endif
    using Entry = const GdalReader* (*)();
    auto entry = reinterpret_cast<Entry>(
        loadModuleEntry(kModuleName, "SHANSHUI_TERRAIN_MODULE", build_dir, "shanshui_gdal_reader", error));
    const GdalReader* r = entry ? entry() : nullptr;
    if (entry && (r == nullptr || r->abi_version != detail::kGdalReaderAbi)) {
      error = std::string(kModuleName) + " is not this build's GDAL module";
      return static_cast<const GdalReader*>(nullptr);
    }
    return r;
  }();
  if (reader == nullptr) throw makeError(name, ": reading it needs the GDAL module ", kModuleName, ": ", error);
  return *reader;
}

// Metres per unit of a vertical unit as GDAL names it ("m", "metre", "ft", "US survey
// foot", ...); 0 when the name is not known.
double verticalUnit(std::string u) {
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return std::tolower(c); });
  if (u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters") return 1.0;
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
  if (u == "us-ft" || u == "ftus" || u == "us survey foot" || u == "foot_us" || u == "us_survey_foot")
    return 1200.0 / 3937.0;
  if (u == "cm" || u == "centimetre" || u == "centimeter") return 0.01;
  if (u == "km" || u == "kilometre" || u == "kilometer") return 1000.0;
  return 0.0;
}

std::string number(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// The most samples a raster may keep: the grid limit, lowered to what the memory budget
// holds at the 8 bytes a sample is read as plus the 4 it is stored as.
std::size_t gridCap() {
  return static_cast<std::size_t>(std::min<std::uintmax_t>(kMaxGridSamples, memoryBudget() / 12));
}

}  // namespace

Heightfield loadGdalRaster(const fs::path& path, const HeightfieldOptions& options) {
  checkInputFile(path, "a raster DEM or height map");
  GdalRaster r;
  if (const std::string error = gdalReader(path.string()).read(path.string(), options.max_samples, gridCap(), &r);
      !error.empty()) {
    throw makeError(path.string(), ": ", error);
  }
  const double* gt = r.geotransform;
  if (!r.georeferenced && r.colour_bands > 1) {
    throw makeError(path.string(), ": height map has ", r.bands,
                    " channels; expected one grey channel (optionally with alpha marking no-data)");
  }
  if (r.georeferenced && (gt[2] != 0.0 || gt[4] != 0.0)) {
    throw makeError(path.string(), ": the grid is rotated (geotransform terms ", gt[2], ", ", gt[4],
                    "); warp it north-up first (gdalwarp)");
  }
  if (r.georeferenced && !(std::isfinite(gt[0]) && std::isfinite(gt[3]) && std::isfinite(gt[1]) &&
                           std::isfinite(gt[5]) && gt[1] > 0.0 && gt[5] != 0.0)) {
    throw makeError(path.string(), ": the georeference has a cell size of ", gt[1], " x ", gt[5],
                    "; expected columns running east (a positive x size) and a non-zero y size");
  }
  const double zUnit = r.z_unit_metres > 0 ? r.z_unit_metres : verticalUnit(r.z_unit);
  if (zUnit <= 0) {
    throw makeError(path.string(), ": heights are in '", r.z_unit,
                    "', a unit shanshui does not know (expected metres, feet, US survey feet, centimetres or "
                    "kilometres)");
  }

  Heightfield h;
  h.columns = r.columns;
  h.rows = r.rows;
  h.elevation = std::move(r.z);
  for (double& z : h.elevation) z *= zUnit;
  h.source = path.filename().string() + ": " + r.driver + " raster, " + std::to_string(r.source_columns) + " x " +
             std::to_string(r.source_rows) + " " + r.type;
  if (zUnit != 1.0) h.notes.push_back("heights converted from " + r.z_unit + " to metres");
  if (r.no_data > 0) {
    h.notes.push_back(std::to_string(r.no_data) + " of " + std::to_string(h.elevation.size()) + " samples are no-data" +
                      (r.has_no_data_value ? " (value " + number("%g", r.no_data_value) + ")" : "") +
                      (options.fill_nodata ? "" : "; they are left out of the mesh (fill them with --fill-nodata)"));
  }
  // The samples read span the whole raster: each covers this many source cells.
  const double spanX = static_cast<double>(r.source_columns) / r.columns,
               spanY = static_cast<double>(r.source_rows) / r.rows;
  if (options.cell_size > 0) {
    h.cell_x = options.cell_size * spanX;
    h.cell_y = options.cell_size * spanY;
    h.origin_y = (h.rows - 1) * h.cell_y;
    h.notes.push_back("cell size " + number("%g", options.cell_size) + " m as given" +
                      (r.georeferenced ? " (the file's georeference is ignored)" : ""));
  } else if (!r.georeferenced) {
    // Images keep the rule they always had: 1 m, or a plausible landform from the relief.
    const auto [lo, hi] = h.elevationRange();
    const int cells = std::max(r.source_columns, r.source_rows) - 1;
    double cell = 1.0;
    if (options.image_relief_ratio > 0 && hi > lo && cells > 0) {
      cell = options.image_relief_ratio * (hi - lo) / cells;
      h.notes.push_back("no georeference: using " + number("%.4g", cell) +
                        " m per pixel, which makes the larger side " + number("%g", options.image_relief_ratio) +
                        " times the relief (give --cell-size)");
    } else {
      h.notes.push_back("no georeference: using 1 m per pixel (give --cell-size)");
    }
    h.notes.push_back("no vertical unit: the stored values are taken as metres (" + number("%g", lo) + " to " +
                      number("%g", hi) + ")");
    h.cell_x = cell * spanX;
    h.cell_y = cell * spanY;
    h.origin_y = (h.rows - 1) * h.cell_y;
  } else {
    // Geographic: a CRS that says so, or, without a CRS, corners that are longitudes and
    // latitudes with cells far below a metre (as for ESRI grids without a .prj).
    const double west = gt[0], top = gt[3], bottom = gt[3] + gt[5] * r.source_rows;
    const double stepX = gt[1] * spanX, stepY = -gt[5] * spanY;  // stepY < 0: a south-up grid
    bool geographic = r.crs == GdalRaster::Crs::Geographic;
    std::string why = "its CRS is geographic";
    if (r.crs == GdalRaster::Crs::None && std::abs(gt[1]) < 0.5 && west >= -360 && west <= 360 &&
        std::min(top, bottom) >= -90.0001 && std::max(top, bottom) <= 90.0001) {
      geographic = true;
      why = "no CRS; corners and cell size read as degrees";
    }
    double mx = r.crs_unit, my = r.crs_unit;
    if (geographic) {
      const double latLo = std::min(top, bottom) * r.crs_unit, latHi = std::max(top, bottom) * r.crs_unit;
      const double latMid = 0.5 * (latLo + latHi);
      const double error = checkGeographicSpan(path.string(), why, latLo, latHi, options);
      mx = metresPerDegreeLongitude(latMid) * r.crs_unit;
      my = metresPerDegreeLatitude(latMid) * r.crs_unit;
      h.notes.push_back("cells of " + number("%.6g", stepX * r.crs_unit) + " x " +
                        number("%.6g", std::abs(stepY) * r.crs_unit) + " degrees (" + why + ") converted to " +
                        number("%.2f", stepX * mx) + " x " + number("%.2f", std::abs(stepY) * my) + " m at latitude " +
                        number("%.4f", latMid) + "; east-west scale error up to " + number("%.2f", error * 100) +
                        " % at the north and south edges");
    } else if (r.crs == GdalRaster::Crs::Projected && r.crs_unit != 1.0) {
      h.notes.push_back("grid units of " + number("%g", r.crs_unit) + " m converted to metres");
    } else if (r.crs != GdalRaster::Crs::Projected) {
      h.notes.push_back("no projected CRS: the grid's units are taken as metres");
    }
    h.cell_x = stepX * mx;
    h.cell_y = stepY * my;
    h.origin_x = (west + 0.5 * stepX) * mx;
    h.origin_y = (top - 0.5 * stepY) * my;
    if (h.cell_y < 0) {  // a south-up grid: flip it so that row 0 is the north edge
      for (int row = 0; row < h.rows / 2; ++row) {
        std::swap_ranges(h.elevation.begin() + static_cast<std::ptrdiff_t>(row) * h.columns,
                         h.elevation.begin() + static_cast<std::ptrdiff_t>(row + 1) * h.columns,
                         h.elevation.begin() + static_cast<std::ptrdiff_t>(h.rows - 1 - row) * h.columns);
      }
      h.cell_y = -h.cell_y;
      h.origin_y += (h.rows - 1) * h.cell_y;
    }
  }
  if (r.factor > 1) {
    h.notes.push_back("read decimated: " + std::to_string(r.source_columns) + " x " + std::to_string(r.source_rows) +
                      " samples averaged in blocks of " + std::to_string(r.factor) + " x " + std::to_string(r.factor) +
                      " to " + std::to_string(h.columns) + " x " + std::to_string(h.rows) + " (at most " +
                      std::to_string(options.max_samples) + ")");
  }
  return h;
}

std::size_t fillNoData(Heightfield& h) {
  const std::size_t holes = h.elevation.size() - h.validCount();
  if (holes == 0 || holes == h.elevation.size()) return 0;
  if (const std::string error = gdalReader(h.source).fill(&h.elevation, h.columns, h.rows); !error.empty()) {
    throw makeError(h.source, ": ", error);
  }
  const std::size_t left = h.elevation.size() - h.validCount();
  h.notes.push_back(std::to_string(holes - left) + " no-data samples filled by inverse-distance interpolation from " +
                    "the valid ones around them (GDALFillNodata)");
  return holes - left;
}

}  // namespace shanshui::terrain
