// Regular elevation grids from heightmap images, USGS ASCII DEM and ESRI ASCII grids.
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace shanshui::terrain {

//! Largest DEM or ASCII grid file read (1 GiB): a bigger one, or an endless device, is refused.
constexpr std::uintmax_t kMaxDemBytes = std::uintmax_t{1} << 30;

inline constexpr double kNoData = std::numeric_limits<double>::quiet_NaN();

//! A grid of elevations in metres, row 0 at the north edge, column 0 at the west edge.
//! Missing samples (NODATA, voids) are NaN. Horizontal coordinates are metres in the
//! file's projected system, or in a local equirectangular projection for geographic input.
struct Heightfield {
  int columns = 0;
  int rows = 0;
  std::vector<double> elevation;   //!< rows * columns, row-major
  double cell_x = 1.0;             //!< metres between columns
  double cell_y = 1.0;             //!< metres between rows
  double origin_x = 0.0;           //!< easting of column 0
  double origin_y = 0.0;           //!< northing of row 0 (the north edge)
  std::string source;              //!< what was read and how it was interpreted, one line
  std::vector<std::string> notes;  //!< conversions applied (degrees to metres, feet to metres, ...)

  double at(int c, int r) const { return elevation[static_cast<std::size_t>(r) * columns + c]; }
  std::size_t validCount() const;
  //! Minimum and maximum of the valid samples; {NaN, NaN} when none.
  std::pair<double, double> elevationRange() const;
};

struct HeightfieldOptions {
  //! Metres between samples. 0 takes it from the file (DEM and ASCII grid headers); images
  //! carry none, so 0 means 1 m there (or see image_relief_ratio). Overrides the file when
  //! given; (0, 1e6].
  double cell_size = 0.0;
  //! Images without cell_size: when above 0, cells that make the larger side this many
  //! times the elevation range (a plausible landform) instead of 1 m.
  double image_relief_ratio = 0.0;
  //! Largest east-west scale error accepted when a geographic grid (degrees) is converted
  //! to metres with one standard parallel at its centre; above it the grid is refused.
  double max_geographic_scale_error = 0.05;
};

//! Loads by extension: .png/.tif/.tiff (single channel; integer values are taken raw, so
//! a 16-bit PNG of metres gives metres), .dem (USGS ASCII DEM), .asc (ESRI ASCII grid).
//! Throws Error naming the file for unreadable, truncated or NODATA-only input.
Heightfield loadHeightfield(const std::filesystem::path& path, const HeightfieldOptions& options = {});

Heightfield loadHeightmapImage(const std::filesystem::path& path, const HeightfieldOptions& options);
Heightfield loadUsgsDem(const std::filesystem::path& path, const HeightfieldOptions& options);
Heightfield loadEsriAscii(const std::filesystem::path& path, const HeightfieldOptions& options);

//! Largest relative east-west scale error at the north or south edge when a grid spanning
//! latitudes [lat_lo, lat_hi] is projected with one standard parallel at its centre.
double eastWestScaleError(double lat_lo_deg, double lat_hi_deg);

//! Metres per degree of latitude and of longitude at latitude `lat_deg` (WGS84 ellipsoid).
double metresPerDegreeLatitude(double lat_deg);
double metresPerDegreeLongitude(double lat_deg);

}  // namespace shanshui::terrain
