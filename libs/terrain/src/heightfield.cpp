#include "shanshui/terrain/heightfield.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"

namespace shanshui::terrain {
namespace fs = std::filesystem;

std::size_t Heightfield::validCount() const {
  return static_cast<std::size_t>(
      std::count_if(elevation.begin(), elevation.end(), [](double z) { return !std::isnan(z); }));
}

std::pair<double, double> Heightfield::elevationRange() const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double z : elevation) {
    if (std::isnan(z)) continue;
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  if (lo > hi) return {kNoData, kNoData};
  return {lo, hi};
}

double metresPerDegreeLatitude(double lat_deg) {
  const double phi = lat_deg * std::numbers::pi / 180.0;
  return 111132.92 - 559.82 * std::cos(2 * phi) + 1.175 * std::cos(4 * phi) - 0.0023 * std::cos(6 * phi);
}

double metresPerDegreeLongitude(double lat_deg) {
  const double phi = lat_deg * std::numbers::pi / 180.0;
  return 111412.84 * std::cos(phi) - 93.5 * std::cos(3 * phi) + 0.118 * std::cos(5 * phi);
}

double eastWestScaleError(double lat_lo_deg, double lat_hi_deg) {
  const double d = std::numbers::pi / 180.0;
  const double mid = std::cos(0.5 * (lat_lo_deg + lat_hi_deg) * d);
  return std::max(std::abs(std::cos(lat_lo_deg * d) / mid - 1), std::abs(std::cos(lat_hi_deg * d) / mid - 1));
}

Heightfield loadHeightmapImage(const fs::path& path, const HeightfieldOptions& options) {
  image::ImageInfo info;
  const image::Image img = image::loadImage(path, &info);
  if (img.channels != 1 && img.channels != 2) {
    throw makeError(path.string(), ": height map has ", img.channels,
                    " channels; expected one grey channel (optionally with alpha marking no-data)");
  }
  Heightfield h;
  h.columns = img.width;
  h.rows = img.height;
  h.cell_x = h.cell_y = options.cell_size > 0 ? options.cell_size : 1.0;
  const double scale = image::normalisationScale(info.depth);
  h.elevation.resize(static_cast<std::size_t>(h.columns) * h.rows);
  for (int y = 0; y < h.rows; ++y) {
    for (int x = 0; x < h.columns; ++x) {
      const bool valid = img.channels == 1 || img.at(x, y, 1) > 0.0f;
      // Integer files: undo OpenImageIO's normalisation and round back to the stored value.
      const double raw = static_cast<double>(img.at(x, y, 0)) * scale;
      const double z = scale > 1.0 ? std::round(raw) : raw;
      h.elevation[static_cast<std::size_t>(y) * h.columns + x] = valid ? z : kNoData;
    }
  }
  h.source = path.filename().string() + ": " + std::to_string(h.columns) + "x" + std::to_string(h.rows) + " " +
             image::depthName(info.depth) + "-bit height map";
  if (options.cell_size <= 0) {
    const auto [lo, hi] = h.elevationRange();
    const int cells = std::max(h.columns, h.rows) - 1;
    if (options.image_relief_ratio > 0 && hi > lo && cells > 0) {
      h.cell_x = h.cell_y = options.image_relief_ratio * (hi - lo) / cells;
      h.notes.push_back("image has no cell size; using " + std::to_string(h.cell_x) +
                        " m per pixel, which makes its larger side " + std::to_string(options.image_relief_ratio) +
                        " times its relief");
    } else {
      h.notes.push_back("image has no cell size; using 1 m per pixel (give --cell-size)");
    }
  }
  return h;
}

Heightfield loadHeightfield(const fs::path& path, const HeightfieldOptions& options) {
  if (!(options.cell_size >= 0.0 && options.cell_size <= 1e6)) {
    throw makeError("--cell-size: ", options.cell_size, " is out of range; expected (0, 1e6] metres");
  }
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  Heightfield h;
  if (ext == ".dem")
    h = loadUsgsDem(path, options);
  else if (ext == ".asc")
    h = loadEsriAscii(path, options);
  else
    h = loadGdalRaster(path, options);
  if (h.validCount() == 0) throw makeError(path.string(), ": no valid elevations (every sample is NODATA)");
  if (options.fill_nodata) fillNoData(h);
  return h;
}

}  // namespace shanshui::terrain
