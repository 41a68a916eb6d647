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

double checkGeographicSpan(const std::string& what, const std::string& why, double lat_lo, double lat_hi,
                           const HeightfieldOptions& options) {
  const double error = eastWestScaleError(lat_lo, lat_hi);
  if (error > options.max_geographic_scale_error || std::abs(0.5 * (lat_lo + lat_hi)) > 85) {
    throw makeError(what, ": cell size is in degrees (", why, ") and the grid spans latitudes ", lat_lo, " to ", lat_hi,
                    "; a local projection would distort east-west distances by ", error * 100,
                    " %; reproject to metres (gdalwarp) or give --cell-size");
  }
  return error;
}

void cropHeightfield(Heightfield& h, const std::array<double, 4>& crop, const std::string& what) {
  const auto [west, south, east, north] = crop;
  for (double f : crop) {
    if (!(f >= 0.0 && f <= 1.0)) throw makeError(what, ": crop ", f, " is outside [0, 1]");
  }
  if (!(east > west && north > south)) {
    throw makeError(what, ": crop [", west, ", ", south, ", ", east, ", ", north,
                    "] is empty; expected west < east and south < north");
  }
  // Columns run west to east, rows north to south.
  const int c0 = static_cast<int>(std::floor(west * (h.columns - 1) + 1e-9)),
            c1 = static_cast<int>(std::ceil(east * (h.columns - 1) - 1e-9));
  const int r0 = static_cast<int>(std::floor((1.0 - north) * (h.rows - 1) + 1e-9)),
            r1 = static_cast<int>(std::ceil((1.0 - south) * (h.rows - 1) - 1e-9));
  if (c1 - c0 < 1 || r1 - r0 < 1) {
    throw makeError(what, ": crop keeps ", c1 - c0 + 1, " x ", r1 - r0 + 1,
                    " samples; expected at least 2 x 2 (widen it)");
  }
  std::vector<double> kept;
  kept.reserve(static_cast<std::size_t>(c1 - c0 + 1) * (r1 - r0 + 1));
  for (int r = r0; r <= r1; ++r)
    for (int c = c0; c <= c1; ++c) kept.push_back(h.at(c, r));
  h.origin_x += c0 * h.cell_x;
  h.origin_y -= r0 * h.cell_y;
  h.notes.push_back("cropped to columns " + std::to_string(c0) + "-" + std::to_string(c1) + " and rows " +
                    std::to_string(r0) + "-" + std::to_string(r1) + " of " + std::to_string(h.columns) + " x " +
                    std::to_string(h.rows));
  h.columns = c1 - c0 + 1;
  h.rows = r1 - r0 + 1;
  h.elevation = std::move(kept);
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
  if (options.crop != std::array<double, 4>{0.0, 0.0, 1.0, 1.0}) cropHeightfield(h, options.crop, path.string());
  if (h.validCount() == 0) throw makeError(path.string(), ": no valid elevations in the crop (every sample is NODATA)");
  if (options.fill_nodata) fillNoData(h);
  return h;
}

}  // namespace shanshui::terrain
