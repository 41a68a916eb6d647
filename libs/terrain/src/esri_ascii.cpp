// ESRI ASCII grid (.asc): "key value" header lines, then nrows lines of ncols values,
// north row first. Cell sizes may be in degrees (geographic grids); those are converted
// to metres with one standard parallel at the grid's centre, or refused when that would
// distort the grid too much.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::terrain {
namespace fs = std::filesystem;

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool parseNumber(const std::string& t, double& v) {
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  return ec == std::errc() && end == t.data() + t.size();
}

// Is the grid in degrees? A .prj beside it decides; without one, corners that are valid
// longitudes/latitudes together with a cell size far below a metre are taken as degrees.
bool looksGeographic(const fs::path& path, double xll, double yll, double cell, int rows, std::string& why) {
  fs::path prj = path;
  prj.replace_extension(".prj");
  std::error_code ec;
  if (fs::exists(fs::symlink_status(prj, ec))) {
    // A sidecar is an input like any other: a regular file of sensible size, or an error
    // naming it (a FIFO would block, a link to /dev/zero would never end).
    const std::string text = readInputFile(prj, "a projection (.prj) sidecar", kMaxSidecarInputBytes);
    const bool projected = text.find("PROJCS") != std::string::npos || text.find("PROJCRS") != std::string::npos;
    why = prj.filename().string() + (projected ? " says projected" : " says geographic");
    return !projected && (text.find("GEOGCS") != std::string::npos || text.find("GEOGCRS") != std::string::npos);
  }
  const bool geographic = cell < 0.5 && xll >= -360 && xll <= 360 && yll >= -90 && yll + rows * cell <= 90.0001;
  why = "no .prj; corner (" + std::to_string(xll) + ", " + std::to_string(yll) + ") and cell size " +
        std::to_string(cell) + " read as degrees";
  return geographic;
}

}  // namespace

Heightfield loadEsriAscii(const fs::path& path, const HeightfieldOptions& options) {
  checkInputFile(path, "an ESRI ASCII grid", kMaxDemBytes);
  std::ifstream in(path);
  if (!in) throw makeError(path.string(), ": cannot open");

  std::map<std::string, double> header;
  std::string line;
  int lineNo = 0;
  std::vector<std::string> firstData;
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream ls(line);
    std::string key, value;
    if (!(ls >> key)) continue;
    double v = 0;
    if (parseNumber(key, v)) {  // first data line
      firstData.push_back(key);
      while (ls >> value) firstData.push_back(value);
      break;
    }
    if (!(ls >> value) || !parseNumber(value, v)) {
      throw makeError(path.string(), ": line ", lineNo, ": expected 'key number', found '", line, "'");
    }
    header[lower(key)] = v;
  }
  auto need = [&](const char* key) {
    const auto it = header.find(key);
    if (it == header.end()) {
      throw makeError(path.string(), ": header lacks '", key, "' (not an ESRI ASCII grid?)");
    }
    return it->second;
  };
  const double ncolsD = need("ncols"), nrowsD = need("nrows");
  if (ncolsD < 1 || nrowsD < 1 || ncolsD != std::floor(ncolsD) || nrowsD != std::floor(nrowsD) ||
      ncolsD * nrowsD > 4e8) {
    throw makeError(path.string(), ": bad grid size ", ncolsD, " x ", nrowsD);
  }
  const int cols = static_cast<int>(ncolsD), rows = static_cast<int>(nrowsD);
  double cellX = 0, cellY = 0;
  if (header.count("cellsize"))
    cellX = cellY = header["cellsize"];
  else {
    cellX = need("dx");
    cellY = need("dy");
  }
  if (!(cellX > 0 && cellY > 0)) throw makeError(path.string(), ": cell size must be positive, is ", cellX);
  const bool centre = header.count("xllcenter") > 0;
  const double xll = centre ? header["xllcenter"] : need("xllcorner");
  const double yll = header.count("yllcenter") ? header["yllcenter"] : need("yllcorner");
  const double noData = header.count("nodata_value") ? header["nodata_value"] : -9999.0;

  checkMemoryNeed(path.string(),
                  "the grid its header promises (" + std::to_string(cols) + " x " + std::to_string(rows) + ")",
                  static_cast<std::uintmax_t>(cols) * rows * sizeof(decltype(Heightfield::elevation)::value_type));
  Heightfield h;
  h.columns = cols;
  h.rows = rows;
  // A header may promise more values than the file can hold (each takes two bytes at least).
  h.elevation.reserve(std::min<std::size_t>(static_cast<std::size_t>(cols) * rows, fs::file_size(path) / 2 + 1));
  auto take = [&](const std::string& t) {
    double v = 0;
    if (!parseNumber(t, v)) {
      throw makeError(path.string(), ": line ", lineNo, ": '", t, "' is not a number");
    }
    if (h.elevation.size() == static_cast<std::size_t>(cols) * rows) {
      throw makeError(path.string(), ": line ", lineNo,
                      ": more values than ncols x nrows = ", static_cast<std::size_t>(cols) * rows);
    }
    h.elevation.push_back(v == noData || !std::isfinite(v) ? kNoData : v);
  };
  for (const auto& t : firstData) take(t);
  while (std::getline(in, line)) {
    ++lineNo;
    std::istringstream ls(line);
    std::string t;
    while (ls >> t) take(t);
  }
  if (h.elevation.size() != static_cast<std::size_t>(cols) * rows) {
    throw makeError(path.string(), ": expected ", static_cast<std::size_t>(cols) * rows, " values (", cols, " x ", rows,
                    "), found ", h.elevation.size(), " (truncated?)");
  }

  std::string why;
  const double yllCorner = centre ? yll - 0.5 * cellY : yll;
  const double westCentre = centre ? xll : xll + 0.5 * cellX;  // the west column's sample
  if (options.cell_size > 0) {
    h.cell_x = h.cell_y = options.cell_size;
    h.origin_x = 0;
    h.origin_y = (rows - 1) * h.cell_y;
  } else if (looksGeographic(path, xll, yllCorner, cellX, rows, why)) {
    const double latLo = yllCorner, latHi = yllCorner + rows * cellY;
    const double latMid = 0.5 * (latLo + latHi);
    const double error = checkGeographicSpan(path.string(), why, latLo, latHi, options);
    h.cell_x = cellX * metresPerDegreeLongitude(latMid);
    h.cell_y = cellY * metresPerDegreeLatitude(latMid);
    h.origin_x = westCentre * metresPerDegreeLongitude(latMid);
    h.origin_y = (yllCorner + (rows - 0.5) * cellY) * metresPerDegreeLatitude(latMid);
    char note[256];
    std::snprintf(note, sizeof note,
                  "cell size %.6g degrees (%s) converted to %.1f m x %.1f m at latitude %.3f; "
                  "east-west scale error up to %.1f %% at the north/south edges",
                  cellX, why.c_str(), h.cell_x, h.cell_y, latMid, error * 100);
    h.notes.emplace_back(note);
  } else {
    h.cell_x = cellX;
    h.cell_y = cellY;
    h.origin_x = westCentre;
    h.origin_y = yllCorner + (rows - 0.5) * cellY;
  }
  h.source = path.filename().string() + ": ESRI ASCII grid, " + std::to_string(cols) + " x " + std::to_string(rows);
  return h;
}

}  // namespace shanshui::terrain
