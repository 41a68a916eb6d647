// USGS ASCII DEM (the "7.5-minute" format): a 1024-byte type A header record, then one
// type B record per south-to-north profile. Fields are fixed width and may touch each
// other (e.g. "0.300000E+020.300000E+02"), so everything is read by column, never by
// whitespace; reals use Fortran 'D' exponents.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::terrain {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kBlock = 1024;
constexpr double kFoot = 0.3048;
constexpr int kVoid = -32767;

class Records {
 public:
  Records(std::string data, fs::path path) : data_(std::move(data)), path_(std::move(path)) {}

  std::string field(std::size_t offset, std::size_t width, const char* what) const {
    if (offset + width > data_.size()) {
      throw makeError(path_.string(), ": file ends at byte ", data_.size(), " but ", what, " is at byte ", offset,
                      " (truncated?)");
    }
    return data_.substr(offset, width);
  }

  double real(std::size_t offset, std::size_t width, const char* what) const {
    std::string s = field(offset, width, what);
    std::replace(s.begin(), s.end(), 'D', 'E');
    std::replace(s.begin(), s.end(), 'd', 'e');
    return parse(s, offset, what);
  }

  long integer(std::size_t offset, std::size_t width, const char* what) const {
    const std::string s = field(offset, width, what);
    const double v = parse(s, offset, what);
    if (v != std::floor(v)) throw bad(offset, what, s);
    // A count, a code or an elevation in the file's units; beyond this it is no whole number
    // a long holds exactly (and the conversion would be undefined).
    constexpr double kLargest = 9.0e15;
    if (std::abs(v) > kLargest) {
      throw makeError(path_.string(), ": byte ", offset, ": ", what, " is '", s, "'; expected a whole number within ±",
                      kLargest);
    }
    return static_cast<long>(v);
  }

  std::size_t size() const { return data_.size(); }
  const fs::path& path() const { return path_; }

 private:
  double parse(const std::string& s, std::size_t offset, const char* what) const {
    std::istringstream in(s);
    double v = 0;
    std::string rest;
    if (!(in >> v) || (in >> rest) || !std::isfinite(v)) throw bad(offset, what, s);
    return v;
  }
  Error bad(std::size_t offset, const char* what, const std::string& s) const {
    return makeError(path_.string(), ": byte ", offset, ": ", what, " is not a number: '", s, "'");
  }
  std::string data_;
  fs::path path_;
};

// Some DEMs are distributed with a line break after every record: pad each line to a
// block so the fixed offsets hold again.
std::string normaliseRecords(const std::string& raw) {
  if (raw.find('\n') == std::string::npos) return raw;
  std::string out;
  std::istringstream in(raw);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::size_t blocks = std::max<std::size_t>(1, (line.size() + kBlock - 1) / kBlock);
    line.resize(blocks * kBlock, ' ');
    out += line;
  }
  return out;
}

}  // namespace

Heightfield loadUsgsDem(const fs::path& path, const HeightfieldOptions& options) {
  const std::string raw = readInputFile(path, "a USGS DEM", kMaxDemBytes);
  const Records rec(normaliseRecords(raw), path);
  if (rec.size() < kBlock) {
    throw makeError(path.string(), ": ", rec.size(), " bytes is shorter than a DEM header record (1024)");
  }

  // Type A record (byte offsets are the standard's 1-based columns minus one).
  const long refSystem = rec.integer(156, 6, "planimetric reference system code");
  const long groundUnits = rec.integer(528, 6, "ground units code");
  const long elevUnits = rec.integer(534, 6, "elevation units code");
  const double dx = rec.real(816, 12, "x resolution");
  const double dy = rec.real(828, 12, "y resolution");
  const double dz = rec.real(840, 12, "z resolution");
  const long profiles = rec.integer(858, 6, "number of profiles");
  if (refSystem < 0 || refSystem > 3) {
    throw makeError(path.string(), ": unknown planimetric reference system code ", refSystem,
                    " (not a USGS ASCII DEM?)");
  }
  if (!(dx > 0 && dy > 0 && dz > 0) || profiles <= 0 || profiles > 100000) {
    throw makeError(path.string(), ": bad header: resolution ", dx, " x ", dy, " x ", dz, ", ", profiles,
                    " profiles (not a USGS ASCII DEM?)");
  }
  if (elevUnits != 1 && elevUnits != 2) {
    throw makeError(path.string(), ": elevation units code ", elevUnits, " (expected 1 feet or 2 metres)");
  }
  const double zUnit = elevUnits == 1 ? kFoot : 1.0;
  const bool geographic = refSystem == 0;
  double xyUnit = 1.0;
  if (groundUnits == 1)
    xyUnit = kFoot;
  else if (groundUnits == 3)
    xyUnit = 1.0 / 3600.0;  // arc-seconds to degrees
  else if (groundUnits != 2) {
    throw makeError(path.string(), ": ground units code ", groundUnits,
                    " is not supported (expected feet, metres or arc-seconds)");
  }

  struct Profile {
    double x = 0, y = 0;
    std::vector<double> z;
  };
  std::vector<Profile> cols(static_cast<std::size_t>(profiles));
  std::size_t offset = kBlock;
  for (long p = 0; p < profiles; ++p) {
    Profile& prof = cols[static_cast<std::size_t>(p)];
    const long m = rec.integer(offset + 12, 6, "profile length");
    if (m <= 0 || m > 1000000) {
      throw makeError(path.string(), ": profile ", p + 1, " has length ", m);
    }
    prof.x = rec.real(offset + 24, 24, "profile x");
    prof.y = rec.real(offset + 48, 24, "profile y");
    const double datum = rec.real(offset + 72, 24, "profile datum elevation");
    prof.z.resize(static_cast<std::size_t>(m));
    for (long k = 0; k < m; ++k) {
      // 146 values fit the first block after the 144-byte profile header, 170 each block after.
      std::size_t at;
      if (k < 146)
        at = offset + 144 + 6 * static_cast<std::size_t>(k);
      else {
        const auto j = static_cast<std::size_t>(k - 146);
        at = offset + kBlock * (1 + j / 170) + 6 * (j % 170);
      }
      const long v = rec.integer(at, 6, "elevation");
      prof.z[static_cast<std::size_t>(k)] = v <= kVoid ? kNoData : (datum + v * dz) * zUnit;
    }
    const std::size_t blocks = m <= 146 ? 1 : 1 + (static_cast<std::size_t>(m - 146) + 169) / 170;
    offset += blocks * kBlock;
  }

  // Place the profiles on one grid: column = profile order, row from the northing.
  double yMin = cols[0].y, yMax = cols[0].y;
  for (const Profile& prof : cols) {
    yMin = std::min(yMin, prof.y);
    yMax = std::max(yMax, prof.y + dy * static_cast<double>(prof.z.size() - 1));
  }
  for (std::size_t c = 1; c < cols.size(); ++c) {
    if (std::abs(cols[c].x - cols[c - 1].x - dx) > 0.01 * dx) {
      throw makeError(path.string(), ": profile ", c + 1, " is at x = ", cols[c].x, ", not one column (", dx,
                      ") east of the previous one");
    }
  }
  // The rows the profiles span, at most a profile's longest (1000000) and a grid's most
  // samples: a profile whose northing is far from the others' would ask for billions.
  const double span = (yMax - yMin) / dy + 1.0;
  if (!(span <= 1000000.0) || span * static_cast<double>(profiles) > static_cast<double>(kMaxGridSamples)) {
    throw makeError(path.string(), ": the profiles' northings span ", yMax - yMin, " at a y resolution of ", dy, ": ",
                    span, " rows x ", profiles, " profiles; expected at most 1000000 rows and ", kMaxGridSamples,
                    " samples");
  }
  Heightfield h;
  h.columns = static_cast<int>(profiles);
  h.rows = static_cast<int>(std::lround(span - 1.0)) + 1;
  h.elevation.assign(static_cast<std::size_t>(h.columns) * h.rows, kNoData);
  for (int c = 0; c < h.columns; ++c) {
    const Profile& prof = cols[static_cast<std::size_t>(c)];
    const long top = std::lround((yMax - prof.y) / dy);  // row of the profile's first (southern) sample
    for (std::size_t k = 0; k < prof.z.size(); ++k) {
      const long r = top - static_cast<long>(k);
      if (r >= 0 && r < h.rows) h.elevation[static_cast<std::size_t>(r) * h.columns + c] = prof.z[k];
    }
  }
  if (geographic) {
    const double latMid = 0.5 * (yMin + yMax) * xyUnit;
    const double latLo = yMin * xyUnit, latHi = yMax * xyUnit;
    const double error = eastWestScaleError(latLo, latHi);
    if (error > options.max_geographic_scale_error && options.cell_size <= 0) {
      throw makeError(path.string(), ": geographic DEM spans latitudes ", latLo, " to ", latHi,
                      "; one local projection would distort east-west distances by ", error * 100,
                      " %; reproject it to metres first or give --cell-size");
    }
    h.cell_x = dx * xyUnit * metresPerDegreeLongitude(latMid);
    h.cell_y = dy * xyUnit * metresPerDegreeLatitude(latMid);
    h.origin_x = cols[0].x * xyUnit * metresPerDegreeLongitude(latMid);
    h.origin_y = yMax * xyUnit * metresPerDegreeLatitude(latMid);
    h.notes.push_back("geographic DEM converted to metres at latitude " + std::to_string(latMid));
  } else {
    h.cell_x = dx * xyUnit;
    h.cell_y = dy * xyUnit;
    h.origin_x = cols[0].x * xyUnit;
    h.origin_y = yMax * xyUnit;
  }
  if (options.cell_size > 0) h.cell_x = h.cell_y = options.cell_size;
  if (elevUnits == 1) h.notes.push_back("elevations converted from feet to metres");
  h.source = path.filename().string() + ": USGS ASCII DEM, " + std::to_string(h.columns) + " profiles x " +
             std::to_string(h.rows) + " rows";
  return h;
}

}  // namespace shanshui::terrain
