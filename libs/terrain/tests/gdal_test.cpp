// Rasters through GDAL: GeoTIFFs (and .hgt, VRT, COG, BigTIFF) written here with GDAL
// itself from functions with known values, read back through shanshui's terrain loader;
// and the hand-written readers as oracles for the formats both read.
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogr_spatialref.h>

#include <cmath>
#include <functional>
#include <memory>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"
#include "test_support.h"

namespace shanshui::terrain {
namespace {

namespace fs = std::filesystem;
using Height = std::function<double(int column, int row)>;

struct Raster {
  int columns = 64, rows = 48;
  GDALDataType type = GDT_Float32;
  double geotransform[6] = {500000, 30, 0, 4100000, 0, -30};  // UTM metres, 30 m cells
  int epsg = 32610;                                           // WGS 84 / UTM 10N; 0: none
  bool georeferenced = true;
  std::optional<double> no_data;
  std::string unit;  //!< the band's unit type
  std::string driver = "GTiff";
  std::vector<std::string> creation;  //!< creation options
};

// Writes `spec` with GDAL: through a MEM dataset and CreateCopy, as every driver supports.
void writeRaster(const fs::path& path, const Raster& spec, const Height& z) {
  GDALAllRegister();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  std::unique_ptr<GDALDataset> ds(mem->Create("", spec.columns, spec.rows, 1, spec.type, nullptr));
  ASSERT_TRUE(ds);
  if (spec.georeferenced) {
    double gt[6];
    std::copy(spec.geotransform, spec.geotransform + 6, gt);
    ds->SetGeoTransform(gt);
    if (spec.epsg) {
      OGRSpatialReference srs;
      srs.importFromEPSG(spec.epsg);
      ds->SetSpatialRef(&srs);
    }
  }
  GDALRasterBand* band = ds->GetRasterBand(1);
  std::vector<double> values(static_cast<std::size_t>(spec.columns) * spec.rows);
  for (int r = 0; r < spec.rows; ++r)
    for (int c = 0; c < spec.columns; ++c) values[static_cast<std::size_t>(r) * spec.columns + c] = z(c, r);
  ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, spec.columns, spec.rows, values.data(), spec.columns, spec.rows, GDT_Float64,
                           0, 0),
            CE_None);
  if (spec.no_data) band->SetNoDataValue(*spec.no_data);
  if (!spec.unit.empty()) band->SetUnitType(spec.unit.c_str());
  std::vector<const char*> options;
  for (const auto& o : spec.creation) options.push_back(o.c_str());
  options.push_back(nullptr);
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(spec.driver.c_str());
  ASSERT_TRUE(driver) << spec.driver;
  GDALDataset* out =
      driver->CreateCopy(path.c_str(), ds.get(), FALSE, const_cast<char**>(options.data()), nullptr, nullptr);
  ASSERT_TRUE(out) << CPLGetLastErrorMsg();
  GDALClose(out);
}

// Great-circle distance on a sphere of mean Earth radius (an oracle independent of the
// ellipsoid series the loader uses; they agree to about 0.5 %).
double haversine(double lat1, double lon1, double lat2, double lon2) {
  const double r = 6371008.8, d = M_PI / 180;
  const double a = std::pow(std::sin((lat2 - lat1) * d / 2), 2) +
                   std::cos(lat1 * d) * std::cos(lat2 * d) * std::pow(std::sin((lon2 - lon1) * d / 2), 2);
  return 2 * r * std::asin(std::sqrt(a));
}

bool mentions(const Heightfield& h, const std::string& what) {
  for (const auto& n : h.notes)
    if (n.find(what) != std::string::npos) return true;
  return false;
}

TEST(GdalRaster, ProjectedGeoTiffOfEverySampleTypeGivesItsHeightsAndCells) {
  test::TempDir dir;
  const Height z = [](int c, int r) { return 1000 + 7 * c - 5 * r; };  // integers: exact in every type
  for (GDALDataType type : {GDT_Int16, GDT_UInt16, GDT_Float32, GDT_Float64}) {
    SCOPED_TRACE(GDALGetDataTypeName(type));
    Raster spec;
    spec.type = type;
    writeRaster(dir / "dem.tif", spec, z);
    const Heightfield h = loadHeightfield(dir / "dem.tif");
    ASSERT_EQ(h.columns, 64);
    ASSERT_EQ(h.rows, 48);
    EXPECT_DOUBLE_EQ(h.cell_x, 30.0);
    EXPECT_DOUBLE_EQ(h.cell_y, 30.0);
    EXPECT_DOUBLE_EQ(h.origin_x, 500015.0);  // the centre of the north-west cell
    EXPECT_DOUBLE_EQ(h.origin_y, 4099985.0);
    for (int r = 0; r < h.rows; ++r)
      for (int c = 0; c < h.columns; ++c) ASSERT_EQ(h.at(c, r), z(c, r)) << c << "," << r;
    EXPECT_NE(h.source.find(GDALGetDataTypeName(type)), std::string::npos) << h.source;
  }
}

// A grid stored south row first (a positive y cell size) comes out north row first, at the
// same place as the same grid stored north-up.
TEST(GdalRaster, SouthUpGridIsTurnedNorthUp) {
  test::TempDir dir;
  Raster spec;
  const double gt[6] = {500000, 30, 0, 4100000 - 48 * 30, 0, 30};
  std::copy(gt, gt + 6, spec.geotransform);
  writeRaster(dir / "south_up.tif", spec, [](int c, int r) { return 10.0 * c + r; });  // row r from the south
  const Heightfield h = loadHeightfield(dir / "south_up.tif");
  ASSERT_EQ(h.rows, 48);
  EXPECT_DOUBLE_EQ(h.cell_y, 30.0);
  EXPECT_DOUBLE_EQ(h.origin_y, 4099985.0);
  EXPECT_EQ(h.at(3, 0), 10.0 * 3 + 47) << "row 0 is the north row";
  EXPECT_EQ(h.at(3, 47), 10.0 * 3);
  spec.geotransform[1] = -30;  // columns running west
  writeRaster(dir / "west.tif", spec, [](int, int) { return 1.0; });
  test::expectErrorNaming([&] { loadHeightfield(dir / "west.tif"); }, "west.tif", "columns running east");
}

TEST(GdalRaster, ProjectedFeetAndVerticalFeetBecomeMetres) {
  test::TempDir dir;
  Raster spec;
  spec.epsg = 2227;  // NAD83 / California zone 3 (US survey feet)
  spec.unit = "ft";
  spec.geotransform[1] = 100;
  spec.geotransform[5] = -100;
  writeRaster(dir / "feet.tif", spec, [](int c, int) { return 100.0 * c; });
  const Heightfield h = loadHeightfield(dir / "feet.tif");
  EXPECT_NEAR(h.cell_x, 100 * 1200.0 / 3937.0, 1e-9);
  EXPECT_NEAR(h.at(3, 0), 300 * 0.3048, 1e-9);
  EXPECT_TRUE(mentions(h, "heights converted from ft")) << h.notes.size();
  EXPECT_TRUE(mentions(h, "grid units of"));
  spec.unit = "furlong";
  writeRaster(dir / "furlong.tif", spec, [](int, int) { return 1.0; });
  test::expectErrorNaming([&] { loadHeightfield(dir / "furlong.tif"); }, "furlong.tif", "'furlong'");
}

TEST(GdalRaster, GeographicGridIsConvertedToMetresAtItsCentreLatitude) {
  test::TempDir dir;
  Raster spec;
  spec.epsg = 4326;
  const double arcsec = 1.0 / 3600;
  spec.columns = 120;
  spec.rows = 90;
  const double gt[6] = {7.0, arcsec, 0, 46.5, 0, -arcsec};
  std::copy(gt, gt + 6, spec.geotransform);
  writeRaster(dir / "alps.tif", spec, [](int c, int r) { return 2000 + c + r; });
  const Heightfield h = loadHeightfield(dir / "alps.tif");
  const double latMid = 46.5 - 45 * arcsec;
  EXPECT_NEAR(h.cell_x / haversine(latMid, 0, latMid, arcsec), 1.0, 0.005);
  EXPECT_NEAR(h.cell_y / haversine(latMid, 0, latMid + arcsec, 0), 1.0, 0.01);
  EXPECT_TRUE(mentions(h, "degrees (its CRS is geographic)"));
  // Without a CRS, degree-like corners and tiny cells are taken as degrees too.
  spec.epsg = 0;
  writeRaster(dir / "nocrs.tif", spec, [](int c, int r) { return 2000 + c + r; });
  const Heightfield n = loadHeightfield(dir / "nocrs.tif");
  EXPECT_DOUBLE_EQ(n.cell_x, h.cell_x);
  EXPECT_TRUE(mentions(n, "read as degrees"));
  // A grid from 10 to 60 degrees north cannot be one local projection.
  spec.epsg = 4326;
  spec.rows = 50;
  const double tall[6] = {7.0, 1.0, 0, 60.0, 0, -1.0};
  std::copy(tall, tall + 6, spec.geotransform);
  writeRaster(dir / "tall.tif", spec, [](int, int) { return 1.0; });
  test::expectErrorNaming([&] { loadHeightfield(dir / "tall.tif"); }, "tall.tif", "degrees");
}

TEST(GdalRaster, NoDataBecomesHolesOrIsFilled) {
  test::TempDir dir;
  Raster spec;
  spec.type = GDT_Int16;
  spec.no_data = -32768;
  // A plane with a 6 x 4 void and the sea (the west 10 columns) as no-data.
  const Height z = [](int c, int r) {
    if (c < 10 || (c >= 30 && c < 36 && r >= 20 && r < 24)) return -32768.0;
    return 500.0 + 4 * c + 2 * r;
  };
  writeRaster(dir / "void.tif", spec, z);
  const Heightfield h = loadHeightfield(dir / "void.tif");
  EXPECT_EQ(h.validCount(), h.elevation.size() - 10 * 48 - 24);
  EXPECT_TRUE(std::isnan(h.at(32, 21)));
  EXPECT_TRUE(mentions(h, "(value -32768)"));
  const auto [lo, hi] = h.elevationRange();
  EXPECT_GE(lo, 500.0) << "no -32768 m cliffs";
  TerrainMeshInfo info;
  heightfieldToMesh(h, {}, &info);
  EXPECT_GT(info.skipped_cells, 0u);

  HeightfieldOptions fill;
  fill.fill_nodata = true;
  const Heightfield f = loadHeightfield(dir / "void.tif", fill);
  EXPECT_EQ(f.validCount(), f.elevation.size());
  // Inside the void the fill is close to the plane it interrupts.
  for (int r = 20; r < 24; ++r)
    for (int c = 30; c < 36; ++c) EXPECT_NEAR(f.at(c, r), 500.0 + 4 * c + 2 * r, 12.0) << c << "," << r;
  EXPECT_TRUE(mentions(f, "filled"));
}

TEST(GdalRaster, LargeRasterIsReadDecimatedWithinTheBudget) {
  test::TempDir dir;
  Raster spec;
  spec.columns = 3000;
  spec.rows = 2000;
  spec.creation = {"TILED=YES", "BIGTIFF=YES", "COMPRESS=DEFLATE"};
  // A plane: a block's average is the plane at the block's centre.
  const Height z = [](int c, int r) { return 100.0 + 0.5 * c + 0.25 * r; };
  writeRaster(dir / "big.tif", spec, z);
  HeightfieldOptions o;
  o.max_samples = 100000;
  const Heightfield h = loadHeightfield(dir / "big.tif", o);
  EXPECT_LE(h.elevation.size(), 100000u);
  const int factor = static_cast<int>(std::lround(h.cell_x / 30.0));
  EXPECT_GE(factor, 7);
  EXPECT_EQ(h.columns, (3000 + factor - 1) / factor);
  EXPECT_DOUBLE_EQ(h.cell_x, 30.0 * 3000 / h.columns);
  for (int r = 0; r + 1 < h.rows; r += 17) {
    for (int c = 0; c + 1 < h.columns; c += 13) {
      const double centreC = c * factor + (factor - 1) / 2.0, centreR = r * factor + (factor - 1) / 2.0;
      ASSERT_NEAR(h.at(c, r), 100.0 + 0.5 * centreC + 0.25 * centreR, 0.01) << c << "," << r;
    }
  }
  EXPECT_TRUE(mentions(h, "read decimated"));
  // The mesh keeps to the vertex budget the decimation was asked for.
  TerrainMeshOptions mo;
  mo.max_vertices = 100000;
  TerrainMeshInfo info;
  const mesh::Mesh m = heightfieldToMesh(h, mo, &info);
  EXPECT_EQ(info.step, 1);
  EXPECT_LE(m.vertexCount(), 100000u);
}

TEST(GdalRaster, CogHgtAndVrtMosaicAreRead) {
  test::TempDir dir;
  const Height z = [](int c, int r) { return 300.0 + c - r; };
  Raster cog;
  cog.driver = "COG";
  writeRaster(dir / "cog.tif", cog, z);
  EXPECT_EQ(loadHeightfield(dir / "cog.tif").at(5, 3), z(5, 3));

  // An SRTM tile: 1201 x 1201 Int16 at 3 arc-seconds, named after its south-west corner.
  Raster hgt;
  hgt.driver = "SRTMHGT";
  hgt.type = GDT_Int16;
  hgt.epsg = 4326;
  hgt.columns = hgt.rows = 1201;
  const double step = 1.0 / 1200;
  const double gt[6] = {7.0 - step / 2, step, 0, 47.0 + step / 2, 0, -step};
  std::copy(gt, gt + 6, hgt.geotransform);
  writeRaster(dir / "N46E007.hgt", hgt, z);
  const Heightfield t = loadHeightfield(dir / "N46E007.hgt");
  EXPECT_EQ(t.columns, 1201);
  EXPECT_EQ(t.at(100, 200), z(100, 200));
  EXPECT_NEAR(t.cell_y, 92.6, 0.5);  // 3 arc-seconds of latitude

  // Two tiles side by side, mosaicked by a VRT: the heights run on across the seam.
  Raster west, east;
  west.columns = east.columns = 32;
  east.geotransform[0] = west.geotransform[0] + 32 * 30;
  writeRaster(dir / "west.tif", west, z);
  writeRaster(dir / "east.tif", east, [&](int c, int r) { return z(c + 32, r); });
  const char* tiles[] = {(dir / "west.tif").c_str(), (dir / "east.tif").c_str()};
  const std::string west_path = (dir / "west.tif").string(), east_path = (dir / "east.tif").string();
  const char* names[] = {west_path.c_str(), east_path.c_str()};
  (void)tiles;
  GDALDatasetH vrt = GDALBuildVRT((dir / "mosaic.vrt").c_str(), 2, nullptr, names, nullptr, nullptr);
  ASSERT_TRUE(vrt);
  GDALClose(vrt);
  const Heightfield m = loadHeightfield(dir / "mosaic.vrt");
  ASSERT_EQ(m.columns, 64);
  for (int c = 28; c < 36; ++c) EXPECT_EQ(m.at(c, 10), z(c, 10)) << c;
}

// The hand-written readers and the OpenImageIO height map reader agree with GDAL on what
// both read (the USGS DEM of St. Helens, the ESRI grid of the hill, 8- and 16-bit images).
TEST(GdalRaster, AgreesWithTheHandWrittenReaders) {
  for (const char* name : {"samples/terrain/mount_st_helens.dem", "samples/terrain/hill.asc"}) {
    SCOPED_TRACE(name);
    const fs::path f = test::sourceDir() / name;
    const Heightfield ours = loadHeightfield(f), gdal = loadGdalRaster(f, {});
    EXPECT_NEAR(ours.cell_x, gdal.cell_x, 1e-6 * ours.cell_x);
    EXPECT_NEAR(ours.cell_y, gdal.cell_y, 1e-6 * ours.cell_y);
    // The same sample at the same place (GDAL may pad the grid with no-data rows).
    std::size_t differ = 0, compared = 0;
    for (int r = 0; r < ours.rows; ++r) {
      for (int c = 0; c < ours.columns; ++c) {
        const double x = ours.origin_x + c * ours.cell_x, y = ours.origin_y - r * ours.cell_y;
        const double gc = (x - gdal.origin_x) / gdal.cell_x, gr = (gdal.origin_y - y) / gdal.cell_y;
        ASSERT_NEAR(gc, std::round(gc), 1e-6) << "the grids are not aligned";
        ASSERT_NEAR(gr, std::round(gr), 1e-6);
        const int ic = static_cast<int>(std::lround(gc)), ir = static_cast<int>(std::lround(gr));
        ASSERT_TRUE(ic >= 0 && ic < gdal.columns && ir >= 0 && ir < gdal.rows) << c << "," << r;
        const double a = ours.at(c, r), b = gdal.at(ic, ir);
        differ += std::isnan(a) != std::isnan(b) || (!std::isnan(a) && std::abs(a - b) > 1e-3);
        ++compared;
      }
    }
    EXPECT_EQ(gdal.validCount(), ours.validCount());
    EXPECT_GT(compared, 20000u);
    EXPECT_EQ(differ, 0u);
  }
  test::TempDir dir;
  image::Image img(7, 5, 1);
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 7; ++x) img.at(x, y) = static_cast<float>(x * 9000 + y * 1000) / 65535.0f;
  image::saveImage(img, dir / "h16.png", image::PixelDepth::UInt16);
  HeightfieldOptions o;
  o.image_relief_ratio = 8;
  const Heightfield a = loadHeightmapImage(dir / "h16.png", o), b = loadGdalRaster(dir / "h16.png", o);
  EXPECT_EQ(a.elevation, b.elevation);
  EXPECT_DOUBLE_EQ(a.cell_x, b.cell_x);
  EXPECT_TRUE(mentions(b, "taken as metres (0 to 58000)")) << "the user is told what was assumed";
}

}  // namespace
}  // namespace shanshui::terrain
