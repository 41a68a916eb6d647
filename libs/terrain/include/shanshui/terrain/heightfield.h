// Regular elevation grids from every raster GDAL reads (GeoTIFF, COG, BigTIFF, .hgt, VRT,
// PNG/TIFF height maps, ...), USGS ASCII DEM and ESRI ASCII grids.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace shanshui::terrain {

//! Largest DEM or ASCII grid file read (1 GiB): a bigger one, or an endless device, is refused.
constexpr std::uintmax_t kMaxDemBytes = std::uintmax_t{1} << 30;

//! Most samples held in memory (2 GiB of doubles): a larger grid must be read decimated.
constexpr std::size_t kMaxGridSamples = std::size_t{1} << 28;

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
  //! Rasters read through GDAL with more samples than this are read decimated by a whole
  //! factor (block averages; GDAL uses the file's overviews where it has them), so that a
  //! 10k x 10k GeoTIFF costs what its mesh needs. 0: no decimation (up to kMaxGridSamples).
  std::size_t max_samples = 0;
  //! No-data samples (voids, the sea) filled by interpolation from the valid ones around
  //! them instead of being left out of the mesh as holes.
  bool fill_nodata = false;
  //! The part of the grid kept: west, south, east and north edges as fractions of its width
  //! and height (x east, y north), so one DEM can give several ranges. {0, 0, 1, 1}: all.
  std::array<double, 4> crop{0.0, 0.0, 1.0, 1.0};
};

//! Loads .dem (USGS ASCII DEM) and .asc (ESRI ASCII grid) with shanshui's own readers and
//! every other raster through GDAL (loadGdalRaster). Throws Error naming the file for
//! unreadable, truncated or NODATA-only input.
Heightfield loadHeightfield(const std::filesystem::path& path, const HeightfieldOptions& options = {});

//! Any raster GDAL opens; band 1 is the height. Georeferenced grids take their cell size
//! and origin from the geotransform, in metres: projected units converted, geographic grids
//! (a geographic CRS, or no CRS with degree-like corners) projected at the centre latitude
//! and refused above max_geographic_scale_error. Heights are scaled by the band's scale and
//! offset and converted from its vertical unit (band unit type, or a compound CRS's
//! vertical unit). No-data values, masks (alpha) and non-finite samples become NaN. Images
//! without georeference keep the image rule (cell_size, image_relief_ratio or 1 m) and say
//! so in `notes`, with the range of heights they took as metres.
Heightfield loadGdalRaster(const std::filesystem::path& path, const HeightfieldOptions& options);

//! Keeps the part of `h` between the fractions west, south, east, north of `crop` (at least
//! two samples a side), moving its origin with it; throws Error naming `what` for a crop
//! outside [0, 1] or with an edge not beyond its opposite.
void cropHeightfield(Heightfield& h, const std::array<double, 4>& crop, const std::string& what);

//! Fills the NaN samples of `h` by inverse-distance interpolation from the valid samples
//! around them (GDAL's GDALFillNodata) and says so in its notes; returns how many.
std::size_t fillNoData(Heightfield& h);

//! The step heights are stored in (whole metres, as SRTM and USGS DEMs store them; tenths;
//! an image's grey levels): the least height difference between neighbouring samples, when
//! every valid sample lies on that step's lattice and the relief spans at least 8 steps;
//! 0 when they do not (heights stored as floats, or too few levels to be a storage step).
double heightStep(const Heightfield& h);

//! The smoothing's width in cells (twice a Gaussian of it less one √2 times as wide), and
//! how many times it runs, each followed by every sample held to within half a step of its
//! stored height (dequantize).
constexpr double kDequantizeSigma = 2.0;
constexpr int kDequantizeSweeps = 2;
//! Samples a band of dequantize's work holds (about 100 bytes each while it runs).
constexpr std::size_t kDequantizeBandSamples = std::size_t{1} << 22;

//! What dequantize found and did.
struct Dequantized {
  double step = 0.0;            //!< heightStep (0: not stored in steps, nothing done)
  double largest_change = 0.0;  //!< metres; at most half a step
};

//! Heights stored in steps make gentle ground a staircase, whose treads' edges are the
//! strongest curvature there (drawn as a net of cracks over a smooth summit). Replaces the
//! staircase by a smooth surface within each sample's step: smoothed (kDequantizeSigma),
//! then every sample held to within half a step of its stored height, kDequantizeSweeps
//! times. The surface then says what the file says, to its precision. No-data samples stay
//! so and are not used; heights not stored in steps are not touched. Says so in `notes`.
//! It works on the box around the samples that hold a height, in bands of rows of at most
//! `band_samples` samples (and an apron of rows the sweeps' reach needs), so its memory is a
//! band's whatever the grid's size; the result does not depend on `band_samples`.
Dequantized dequantize(Heightfield& h, double sigma = kDequantizeSigma, int sweeps = kDequantizeSweeps,
                       std::size_t band_samples = kDequantizeBandSamples);
//! How many cells the smoothing of one sweep reaches (dequantize's kernel, and its padding).
int dequantizeReach(double sigma);

//! Most times finer upsample() makes a grid along each side.
constexpr int kMostUpsample = 8;

//! A grid `factor` times finer along each side: (columns − 1)·factor + 1 by
//! (rows − 1)·factor + 1 samples over the same ground, the new ones by bicubic
//! (Catmull-Rom) interpolation along the rows and then the columns, so every stored sample keeps its
//! height and a coarse grid's coasts and silhouettes are curves, not the grid's facets. A new
//! sample between stored ones of which any is no data is no data (the holes keep their
//! extent); heights beyond the edge continue the last three samples' parabola. Says so in `notes`. factor 1: nothing
//! done; outside [1, kMostUpsample], or a result over kMaxGridSamples: Error naming `what`.
void upsample(Heightfield& h, int factor, const std::string& what);

//! How many samples upsample(h, factor) makes: ((columns − 1)·factor + 1)·((rows − 1)·factor + 1),
//! as a double (no overflow).
double upsampledSamples(const Heightfield& h, int factor);

//! The least factor (at most kMostUpsample) that gives the grid's larger side at least
//! `least_side` samples, within `max_samples` in all; 1 when it has them already.
int upsampleFactor(const Heightfield& h, int least_side, std::size_t max_samples);

//! The OpenImageIO height map reader that GDAL replaced for images; kept as the tests' oracle.
Heightfield loadHeightmapImage(const std::filesystem::path& path, const HeightfieldOptions& options);
Heightfield loadUsgsDem(const std::filesystem::path& path, const HeightfieldOptions& options);
Heightfield loadEsriAscii(const std::filesystem::path& path, const HeightfieldOptions& options);

//! Largest relative east-west scale error at the north or south edge when a grid spanning
//! latitudes [lat_lo, lat_hi] is projected with one standard parallel at its centre.
double eastWestScaleError(double lat_lo_deg, double lat_hi_deg);

//! The east-west scale error of a degree grid spanning latitudes [lat_lo, lat_hi] projected
//! at its centre, after checking it against options.max_geographic_scale_error (and the
//! centre against the poles); throws Error naming `what` and `why` (how the degrees were
//! recognised) above it.
double checkGeographicSpan(const std::string& what, const std::string& why, double lat_lo, double lat_hi,
                           const HeightfieldOptions& options);

//! Metres per degree of latitude and of longitude at latitude `lat_deg` (WGS84 ellipsoid).
double metresPerDegreeLatitude(double lat_deg);
double metresPerDegreeLongitude(double lat_deg);

}  // namespace shanshui::terrain
