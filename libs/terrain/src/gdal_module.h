// The interface between the terrain library and its GDAL module (libshanshui_terrain_gdal.so,
// loaded on first use; see shanshui/core/module.h). The module only talks to GDAL; what the
// numbers mean (units, georeference, no-data notes) is decided in gdal_raster.cpp.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace shanshui::terrain::detail {

//! Band 1 of a raster as GDAL reads it, possibly decimated.
struct GdalRaster {
  std::string driver, type;  //!< GDAL's driver and sample type names
  int source_columns = 0, source_rows = 0;
  int columns = 0, rows = 0;  //!< as read (source / factor, rounded up)
  int factor = 1;             //!< whole decimation factor (block averages)
  int bands = 0, colour_bands = 0;
  std::vector<double> z;    //!< rows * columns, row 0 first as stored; NaN = no-data or masked
  std::size_t no_data = 0;  //!< samples made NaN
  bool has_no_data_value = false;
  double no_data_value = 0.0;
  double scale = 1.0, offset = 0.0;  //!< applied to z already
  std::string z_unit;                //!< band unit type, or the compound CRS's vertical unit name
  double z_unit_metres = 0.0;        //!< metres per z_unit from the CRS; 0: unknown (the name decides)
  bool georeferenced = false;
  double geotransform[6] = {0, 1, 0, 0, 0, 1};
  enum class Crs { None, Geographic, Projected, Other } crs = Crs::None;
  double crs_unit = 1.0;  //!< degrees (geographic) or metres (projected) per georeference unit
};

struct GdalReader {
  int abi_version;
  //! Reads band 1 of `path`, decimated by the smallest whole factor that brings it within
  //! `max_samples` (0: no limit), refusing more than `cap` samples. Returns "" or the error.
  std::string (*read)(const std::string& path, std::size_t max_samples, std::size_t cap, GdalRaster* out);
  //! GDALFillNodata over a rows x columns grid whose NaN samples are the holes.
  std::string (*fill)(std::vector<double>* z, int columns, int rows);
};
constexpr int kGdalReaderAbi = 1;

}  // namespace shanshui::terrain::detail
