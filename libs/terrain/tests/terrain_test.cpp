#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "mesh_checks.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/image/image_io.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"
#include "stepped_hill.h"
#include "test_support.h"

namespace shanshui::terrain {
namespace {

const std::filesystem::path kStHelens = test::sourceDir() / "samples/terrain/mount_st_helens.dem";
std::filesystem::path shared(const char* name) {
  return test::sharedData() / "terrain" / name;
}

// Great-circle distance on a sphere of mean Earth radius: an oracle independent of the
// ellipsoid series the importer uses (they agree to about 0.5 %).
double haversine(double lat1, double lon1, double lat2, double lon2) {
  const double r = 6371008.8, d = M_PI / 180;
  const double a = std::pow(std::sin((lat2 - lat1) * d / 2), 2) +
                   std::cos(lat1 * d) * std::cos(lat2 * d) * std::pow(std::sin((lon2 - lon1) * d / 2), 2);
  return 2 * r * std::asin(std::sqrt(a));
}

TEST(UsgsDem, MountStHelensHeaderAndExtentsAgree) {
  const Heightfield h = loadHeightfield(kStHelens);
  EXPECT_EQ(h.columns, 327);  // profiles in the type A record
  EXPECT_DOUBLE_EQ(h.cell_x, 30.0);
  EXPECT_DOUBLE_EQ(h.cell_y, 30.0);
  const auto [lo, hi] = h.elevationRange();
  EXPECT_DOUBLE_EQ(lo, 682.0);  // the header's minimum and maximum elevations
  EXPECT_DOUBLE_EQ(hi, 2543.0);
  // The quadrangle's corners (header) span 557813..567602 E and 5107990..5121979 N; the
  // grid of 30 m posts lies inside them.
  EXPECT_GE(h.origin_x, 557813.0 - 30);
  EXPECT_LE(h.origin_x + (h.columns - 1) * h.cell_x, 567602.0 + 30);
  EXPECT_LE(h.origin_y, 5121979.0 + 30);
  EXPECT_GE(h.origin_y - (h.rows - 1) * h.cell_y, 5107990.0 - 30);
  EXPECT_GT(h.rows * h.cell_y, 13000.0);
  // Profiles follow the quadrangle's slanted edges: corners of the grid are void.
  EXPECT_LT(h.validCount(), h.elevation.size());
  EXPECT_TRUE(std::isnan(h.at(0, 0)));
  // First profile: x 557820, first sample at y 5121240 is 909 m (read off the file).
  EXPECT_DOUBLE_EQ(h.origin_x, 557820.0);
  const int row = static_cast<int>(std::lround((h.origin_y - 5121240.0) / 30.0));
  EXPECT_DOUBLE_EQ(h.at(0, row), 909.0);
}

TEST(HeightmapImage, Jacksboro16BitPngIsInMetres) {
  SHANSHUI_REQUIRE_FILE(shared("jacksboro_fault_dem_u16.png"));
  HeightfieldOptions o;
  o.cell_size = 90;
  const Heightfield h = loadHeightfield(shared("jacksboro_fault_dem_u16.png"), o);
  EXPECT_EQ(h.columns, 403);
  EXPECT_EQ(h.rows, 344);
  const auto [lo, hi] = h.elevationRange();
  EXPECT_DOUBLE_EQ(lo, 236.0);
  EXPECT_DOUBLE_EQ(hi, 1076.0);
  EXPECT_DOUBLE_EQ(h.cell_x, 90.0);
}

TEST(HeightmapImage, EightBitPngAndSixteenBitTiffGiveRawValues) {
  test::TempDir dir;
  image::Image img(5, 3, 1);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) img.at(x, y) = static_cast<float>(x * 3 + y * 50) / 255.0f;
  image::saveImage(img, dir / "h8.png", image::PixelDepth::UInt8);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) img.at(x, y) = static_cast<float>(x * 1000 + y * 20000) / 65535.0f;
  image::saveImage(img, dir / "h16.tif", image::PixelDepth::UInt16);
  const Heightfield h8 = loadHeightfield(dir / "h8.png");
  const Heightfield h16 = loadHeightfield(dir / "h16.tif");
  ASSERT_EQ(h8.columns, 5);
  ASSERT_EQ(h16.rows, 3);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 5; ++x) {
      EXPECT_EQ(h8.at(x, y), x * 3 + y * 50);  // row 0 of the image is the north row
      EXPECT_EQ(h16.at(x, y), x * 1000 + y * 20000);
    }
  }
  EXPECT_FALSE(h8.notes.empty());  // no cell size in an image: the user is told
}

TEST(EsriAscii, GeographicBcCoastIsConvertedToMetres) {
  SHANSHUI_REQUIRE_FILE(shared("bc_coast_topobathy.asc"));
  const Heightfield h = loadHeightfield(shared("bc_coast_topobathy.asc"));
  EXPECT_EQ(h.columns, 120);
  EXPECT_EQ(h.rows, 91);
  const auto [lo, hi] = h.elevationRange();
  EXPECT_DOUBLE_EQ(lo, -1437.0);
  EXPECT_DOUBLE_EQ(hi, 2205.0);
  // One cell of 0.033310 degrees at the centre latitude, measured on the sphere.
  const double latMid = 48.016369 + 91 * 0.033310 / 2;
  EXPECT_NEAR(h.cell_x / haversine(latMid, 0, latMid, 0.033310), 1.0, 0.005);
  EXPECT_NEAR(h.cell_y / haversine(latMid, 0, latMid + 0.033310, 0), 1.0, 0.01);
  ASSERT_FALSE(h.notes.empty());
  EXPECT_NE(h.notes[0].find("degrees"), std::string::npos);
}

TEST(EsriAscii, TooTallGeographicGridIsRefused) {
  test::TempDir dir;
  std::ofstream f(dir / "tall.asc");
  f << "ncols 2\nnrows 100\nxllcorner 10\nyllcorner 20\ncellsize 0.4\nNODATA_value -9999\n";
  for (int i = 0; i < 200; ++i) f << "1 ";
  f.close();
  try {
    loadHeightfield(dir / "tall.asc");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("degrees"), std::string::npos) << e.what();
  }
  HeightfieldOptions o;
  o.cell_size = 100;  // the user says what a cell is: accepted
  EXPECT_EQ(loadHeightfield(dir / "tall.asc", o).cell_x, 100.0);
}

// The grid a header promises is weighed against the memory budget before it is read.
TEST(EsriAscii, AGridOverTheMemoryBudgetIsRefusedFromItsHeader) {
  test::TempDir dir;
  std::ofstream f(dir / "wide.asc");
  f << "ncols 600\nnrows 500\nxllcorner 0\nyllcorner 0\ncellsize 10\n";
  for (int i = 0; i < 600 * 500; ++i) f << (i % 7) << (i % 600 == 599 ? "\n" : " ");
  f.close();
  setMemoryBudget(600 * 500 * sizeof(double) * 2);
  EXPECT_EQ(loadHeightfield(dir / "wide.asc").columns, 600);
  setMemoryBudget(600 * 500);
  test::expectErrorNaming([&] { loadHeightfield(dir / "wide.asc"); }, "wide.asc", "more than the memory budget");
  setMemoryBudget(0);
}

// The .prj beside an ESRI grid is read like any input: a FIFO, a directory or an endless
// device is an error naming it, never a hang (issue 48).
TEST(EsriAscii, PrjSidecarIsCheckedLikeAnInput) {
  test::TempDir dir;
  const std::string grid = "ncols 2\nnrows 2\nxllcorner 10\nyllcorner 20\ncellsize 0.001\n1 2\n3 4\n";
  std::ofstream(dir / "fifo.asc") << grid;
  ASSERT_EQ(::mkfifo((dir / "fifo.prj").c_str(), 0600), 0);
  std::ofstream(dir / "folder.asc") << grid;
  std::filesystem::create_directory(dir / "folder.prj");
  std::ofstream(dir / "zero.asc") << grid;
  std::filesystem::create_symlink("/dev/zero", dir / "zero.prj");
  test::expectErrorNaming([&] { loadHeightfield(dir / "fifo.asc"); }, "fifo.prj", "not a regular file");
  test::expectErrorNaming([&] { loadHeightfield(dir / "folder.asc"); }, "folder.prj", "is a directory");
  test::expectErrorNaming([&] { loadHeightfield(dir / "zero.asc"); }, "zero.prj", "not a regular file");
  std::ofstream(dir / "utm.asc") << grid;
  std::ofstream(dir / "utm.prj") << "PROJCS[\"WGS 84 / UTM zone 10N\"]";
  EXPECT_DOUBLE_EQ(loadHeightfield(dir / "utm.asc").cell_x, 0.001) << "projected: the cell size as it is";
}

TEST(Terrain, BadInputIsNamedClearly) {
  test::TempDir dir;
  std::ofstream(dir / "nodata.asc") << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n"
                                       "NODATA_value -9999\n-9999 -9999\n-9999 -9999\n";
  std::ofstream(dir / "short.asc") << "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4 5\n";
  std::ofstream(dir / "nohead.asc") << "1 2 3\n";
  {
    std::ifstream in(kStHelens, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir / "cut.dem", std::ios::binary).write(bytes.data(), 5000);
    std::ofstream(dir / "header.dem", std::ios::binary).write(bytes.data(), 600);
  }
  std::ofstream(dir / "text.dem") << std::string(2048, 'x');
  std::ofstream(dir / "notes.txt") << "not a height map\n";
  image::saveImage(image::Image(4, 4, 3, 0.5f), dir / "rgb.png");
  const std::pair<const char*, const char*> cases[] = {{"nodata.asc", "no valid elevations"},
                                                       {"short.asc", "expected 6 values"},
                                                       {"nohead.asc", "lacks 'ncols'"},
                                                       {"cut.dem", "truncated"},
                                                       {"header.dem", "shorter than a DEM header"},
                                                       {"text.dem", "not a number"},
                                                       {"rgb.png", "3 channels"},
                                                       {"missing.dem", "no such file"},
                                                       {"notes.txt", "not a raster GDAL can read"},
                                                       {"missing.tif", "no such file"}};
  for (const auto& [file, what] : cases) {
    test::expectErrorNaming([&] { loadHeightfield(dir / file); }, file, what);
  }
}

Heightfield ramp(int cols, int rows) {
  Heightfield h;
  h.columns = cols;
  h.rows = rows;
  h.cell_x = 2.0;
  h.cell_y = 3.0;
  h.origin_x = 500000;
  h.origin_y = 4000000;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) h.elevation.push_back(10.0 * c + 0.5 * r * r);
  return h;
}

TEST(Terrain, CropKeepsThePartAskedForAndMovesTheOrigin) {
  Heightfield h = ramp(11, 6);  // columns west to east, rows north to south
  const Heightfield whole = h;
  cropHeightfield(h, {0.2, 0.0, 0.6, 0.4}, "ramp");
  ASSERT_EQ(h.columns, 5);  // columns 2..6
  ASSERT_EQ(h.rows, 3);     // the southern rows 3..5
  for (int r = 0; r < h.rows; ++r)
    for (int c = 0; c < h.columns; ++c) EXPECT_EQ(h.at(c, r), whole.at(c + 2, r + 3));
  EXPECT_DOUBLE_EQ(h.origin_x, whole.origin_x + 2 * whole.cell_x);
  EXPECT_DOUBLE_EQ(h.origin_y, whole.origin_y - 3 * whole.cell_y);
  Heightfield g = whole;
  test::expectErrorNaming([&] { cropHeightfield(g, {0.5, 0.0, 0.5, 1.0}, "ramp.asc"); }, "ramp.asc", "is empty");
  test::expectErrorNaming([&] { cropHeightfield(g, {0.0, 0.0, 1.5, 1.0}, "ramp.asc"); }, "ramp.asc", "outside [0, 1]");
  test::expectErrorNaming(
      [&] {
        cropHeightfield(g, {0.0, 0.0, 1e-12, 1.0}, "ramp.asc");
      },
      "ramp.asc", "at least 2 x 2");
}

TEST(TerrainMesh, GridMeshMatchesTheSamplesAndFacesUp) {
  const Heightfield h = ramp(7, 5);
  TerrainMeshInfo info;
  TerrainMeshOptions o;
  o.z_scale = 2.0;
  const mesh::Mesh m = heightfieldToMesh(h, o, &info);
  test::expectCleanMesh(m, "ramp");
  EXPECT_EQ(m.vertexCount(), 35u);
  EXPECT_EQ(m.triangleCount(), 2u * 6 * 4);
  for (const auto& t : m.triangles) {
    const auto a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0);  // counter-clockwise seen from above
  }
  // Every vertex sits on its sample: x, y back on the grid, z = elevation * z_scale.
  for (const auto& p : m.positions) {
    const double c = (p.x + info.offset.x - h.origin_x) / h.cell_x;
    const double r = (h.origin_y - p.y - info.offset.y) / h.cell_y;
    ASSERT_NEAR(c, std::round(c), 1e-9);
    ASSERT_NEAR(r, std::round(r), 1e-9);
    EXPECT_DOUBLE_EQ(p.z, 2.0 * h.at(static_cast<int>(std::round(c)), static_cast<int>(std::round(r))));
  }
  const mesh::Bounds b = mesh::bounds(m);
  EXPECT_NEAR(b.centre().x, 0.0, 1e-9);  // recentred in x and y only
  EXPECT_NEAR(b.size().x, 12.0, 1e-9);
  EXPECT_NEAR(b.size().y, 12.0, 1e-9);
}

TEST(TerrainMesh, MissingSamplesAndDecimation) {
  Heightfield h = ramp(5, 5);
  h.elevation[0] = kNoData;  // one corner of the first cell gone: that cell keeps one triangle
  const mesh::Mesh m = heightfieldToMesh(h, {});
  EXPECT_EQ(m.vertexCount(), 24u);
  EXPECT_EQ(m.triangleCount(), 2u * 16 - 1);
  TerrainMeshOptions o;
  o.max_vertices = 9;
  TerrainMeshInfo info;
  const mesh::Mesh small = heightfieldToMesh(ramp(9, 9), o, &info);
  EXPECT_EQ(info.step, 3);  // the smallest step that fits: 3x3 samples
  EXPECT_EQ(small.vertexCount(), 9u);
  Heightfield line = ramp(5, 1);
  EXPECT_THROW(heightfieldToMesh(line, {}), Error);
  o = {};
  o.z_scale = 0;
  EXPECT_THROW(heightfieldToMesh(h, o), Error);
}

TEST(TerrainMesh, StHelensMeshIsCleanAndKeepsElevations) {
  const Heightfield h = loadHeightfield(kStHelens);
  TerrainMeshOptions o;
  o.max_vertices = 40000;
  const mesh::Mesh m = heightfieldToMesh(h, o);
  test::expectCleanMesh(m, "st helens");
  EXPECT_LE(m.vertexCount(), 40000u);
  const mesh::Bounds b = mesh::bounds(m);
  EXPECT_GE(b.min.z, 682.0);
  EXPECT_LE(b.max.z, 2543.0);
  EXPECT_GT(b.size().x, 9000.0);
}

}  // namespace
}  // namespace shanshui::terrain

namespace shanshui::terrain {

// A smooth hill stored in whole metres, as SRTM and USGS DEMs store heights: on its gentle
// top the steps' edges were the strongest curvature. Smoothed within its steps, every
// sample moves at most half a metre and the curvature (the discrete Laplacian) comes within
// a twentieth of its error against the true hill, on a steep hill and on a gentle one.
TEST(Dequantize, HeightsInWholeMetresBecomeTheSmoothHillWithinHalfAMetre) {
  for (double height : {400.0, 40.0}) {
    Heightfield h = test::steppedHill(height, 1.0);
    const Heightfield stored = h;
    const auto [z_before, lap_before] = test::hillErrors(h, height);
    const Dequantized d = dequantize(h);
    const auto [z_after, lap_after] = test::hillErrors(h, height);
    EXPECT_DOUBLE_EQ(d.step, 1.0);
    EXPECT_LE(d.largest_change, 0.5 + 1e-12);
    for (std::size_t i = 0; i < h.elevation.size(); ++i)
      ASSERT_LE(std::abs(h.elevation[i] - stored.elevation[i]), 0.5 + 1e-12) << i;
    EXPECT_LT(lap_after, 0.05 * lap_before) << height << " m: " << lap_before << " -> " << lap_after;
    EXPECT_LT(z_after, 0.4 * z_before) << height << " m: " << z_before << " -> " << z_after;
    EXPECT_NE(h.notes.back().find("steps of 1 m"), std::string::npos) << h.notes.back();
  }
}

// Heights stored as floats, or in too few levels to be a storage step, are left as they
// are; tenths and no-data samples are handled: a no-data sample stays so and does not pull
// its neighbours.
TEST(Dequantize, OnlyHeightsStoredInStepsAreTouchedAndNoDataStaysSo) {
  Heightfield smooth = test::steppedHill(400.0, 0.0);
  const Heightfield before = smooth;
  EXPECT_EQ(dequantize(smooth).step, 0.0);
  EXPECT_EQ(smooth.elevation, before.elevation);
  EXPECT_TRUE(smooth.notes.empty());

  Heightfield mesa = test::steppedHill(400.0, 100.0);  // five levels: a terrace model, not storage
  EXPECT_EQ(heightStep(mesa), 0.0);

  Heightfield tenths = test::steppedHill(40.0, 0.1);
  tenths.elevation[100 * 200 + 100] = kNoData;
  const Heightfield stored = tenths;
  const Dequantized d = dequantize(tenths);
  EXPECT_NEAR(d.step, 0.1, 1e-9);
  EXPECT_TRUE(std::isnan(tenths.elevation[100 * 200 + 100]));
  for (std::size_t i = 0; i < tenths.elevation.size(); ++i) {
    if (std::isnan(stored.elevation[i])) continue;
    ASSERT_TRUE(std::isfinite(tenths.elevation[i])) << i;
    ASSERT_LE(std::abs(tenths.elevation[i] - stored.elevation[i]), 0.05 + 1e-9) << i;
  }
}

// The work is done on the box around the heights and in bands of rows, so that its memory is
// a band's: a hill in tenths inside a wide frame of no data, with a hole, is smoothed the same
// to the bit in bands of one row (an apron of 39 rows each side) as in one band; the frame
// stays no data; and the same hill with the frame cut off differs only within the kernel's
// reach of the cut (where the frame's no data gave way to the grid's edge), not beyond it.
TEST(Dequantize, BandsOfRowsAndTheBoxAroundTheHeightsGiveTheWholeGridsResult) {
  const int side = 200, frame = 30;
  Heightfield framed = test::steppedHill(40.0, 0.1);
  ASSERT_EQ(framed.columns, side);
  for (int r = 0; r < side; ++r) {
    for (int c = 0; c < side; ++c) {
      if (r < frame || c < frame || r >= side - frame || c >= side - 2 * frame || (r == 100 && c == 90))
        framed.elevation[static_cast<std::size_t>(r) * side + c] = kNoData;
    }
  }
  Heightfield whole = framed, banded = framed;
  const Dequantized a = dequantize(whole);
  const Dequantized b = dequantize(banded, kDequantizeSigma, kDequantizeSweeps, 1);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.largest_change, b.largest_change);
  for (std::size_t i = 0; i < whole.elevation.size(); ++i) {
    if (std::isnan(framed.elevation[i])) {
      ASSERT_TRUE(std::isnan(whole.elevation[i]) && std::isnan(banded.elevation[i])) << i;
      continue;
    }
    ASSERT_EQ(whole.elevation[i], banded.elevation[i]) << i;
    ASSERT_LE(std::abs(whole.elevation[i] - framed.elevation[i]), 0.05 + 1e-9) << i;
  }
  // A height in each corner of the grid makes the box the whole grid: the hill, beyond the
  // sweeps' reach of the corners, is smoothed the same to the bit as in its own box.
  Heightfield cornered = framed;
  for (int k : {0, side - 1}) {
    for (int j : {0, side - 1}) cornered.elevation[static_cast<std::size_t>(k) * side + j] = 0.0;
  }
  dequantize(cornered);
  for (std::size_t i = 0; i < whole.elevation.size(); ++i) {
    if (std::isnan(framed.elevation[i])) continue;
    ASSERT_EQ(cornered.elevation[i], whole.elevation[i]) << i;
  }
  // The frame cut off: the same wherever the edge (an extension) is beyond the sweeps' reach.
  Heightfield cut;
  cut.columns = side - 3 * frame;
  cut.rows = side - 2 * frame;
  for (int r = frame; r < side - frame; ++r) {
    for (int c = frame; c < side - 2 * frame; ++c) cut.elevation.push_back(framed.at(c, r));
  }
  cut.elevation[static_cast<std::size_t>(100 - frame) * cut.columns + 90 - frame] = kNoData;
  dequantize(cut);
  const int reach = kDequantizeSweeps * dequantizeReach(kDequantizeSigma);
  int compared = 0;
  for (int r = reach; r < cut.rows - reach; ++r) {
    for (int c = reach; c < cut.columns - reach; ++c) {
      const double z = cut.at(c, r);
      if (std::isnan(z)) continue;
      ASSERT_NEAR(z, whole.at(c + frame, r + frame), 1e-9) << c << " " << r;
      ++compared;
    }
  }
  EXPECT_GT(compared, 1000);
}

}  // namespace shanshui::terrain

namespace shanshui::terrain {
namespace {

// A smooth landform known everywhere: two wavelengths of about 7 and 11 cells of the coarse
// grid, so a coarse grid resolves it but draws it with visible facets.
double waves(double x, double y) {
  return 300.0 * std::sin(0.9 * x) * std::cos(0.55 * y) + 80.0 * std::cos(0.35 * x + 0.6 * y);
}

Heightfield sampled(int columns, int rows, double cell) {
  Heightfield h;
  h.columns = columns;
  h.rows = rows;
  h.cell_x = h.cell_y = cell;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) h.elevation.push_back(waves(c * cell, r * cell));
  return h;
}

}  // namespace

// Made four times finer, the grid keeps every stored sample to the bit, covers the same
// ground, and lies on the true landform between them far closer than straight lines between
// the stored samples do (bilinear interpolation, what the coarse mesh's triangles draw).
TEST(Upsample, KeepsTheStoredSamplesAndFollowsTheLandformBetweenThem) {
  const Heightfield coarse = sampled(30, 20, 1.0);
  Heightfield fine = coarse;
  upsample(fine, 4, "test");
  ASSERT_EQ(fine.columns, 29 * 4 + 1);
  ASSERT_EQ(fine.rows, 19 * 4 + 1);
  EXPECT_DOUBLE_EQ(fine.cell_x, 0.25);
  EXPECT_DOUBLE_EQ(fine.cell_y, 0.25);
  for (int r = 0; r < coarse.rows; ++r) {
    for (int c = 0; c < coarse.columns; ++c) ASSERT_EQ(fine.at(4 * c, 4 * r), coarse.at(c, r)) << c << " " << r;
  }
  // Inside, away from the edge (where the cubic continues the edge instead of the landform).
  double cubic = 0.0, linear = 0.0;
  for (int r = 8; r < fine.rows - 8; ++r) {
    for (int c = 8; c < fine.columns - 8; ++c) {
      const double x = c * 0.25, y = r * 0.25, truth = waves(x, y);
      const int c0 = c / 4, r0 = r / 4;
      const double fx = x - c0, fy = y - r0;
      const double bilinear = (1 - fy) * ((1 - fx) * coarse.at(c0, r0) + fx * coarse.at(c0 + 1, r0)) +
                              fy * ((1 - fx) * coarse.at(c0, r0 + 1) + fx * coarse.at(c0 + 1, r0 + 1));
      cubic = std::max(cubic, std::abs(fine.at(c, r) - truth));
      linear = std::max(linear, std::abs(bilinear - truth));
    }
  }
  EXPECT_LT(cubic, 0.2 * linear) << cubic << " against " << linear;
  EXPECT_NE(fine.notes.back().find("4 times finer"), std::string::npos) << fine.notes.back();
}

// No data stays where it was: a new sample is no data exactly when a stored sample at a
// corner of its cell is, so a hole keeps its extent and no stand-in height shows; everything
// else is finite. Factor 1 changes nothing; a factor outside [1, 8] is refused by name.
TEST(Upsample, HolesKeepTheirExtentAndBadFactorsAreRefused) {
  Heightfield coarse = sampled(12, 10, 30.0);
  coarse.elevation[4 * 12 + 5] = kNoData;                              // one sample
  for (int c = 0; c < 3; ++c) coarse.elevation[9 * 12 + c] = kNoData;  // a corner of sea
  Heightfield fine = coarse;
  upsample(fine, 3, "objects.0.upsample");
  for (int r = 0; r < fine.rows; ++r) {
    for (int c = 0; c < fine.columns; ++c) {
      const int c0 = c / 3, r0 = r / 3, c1 = std::min(c0 + (c % 3 ? 1 : 0), 11), r1 = std::min(r0 + (r % 3 ? 1 : 0), 9);
      const bool hole = std::isnan(coarse.at(c0, r0)) || std::isnan(coarse.at(c1, r0)) ||
                        std::isnan(coarse.at(c0, r1)) || std::isnan(coarse.at(c1, r1));
      ASSERT_EQ(std::isnan(fine.at(c, r)), hole) << c << " " << r;
      if (!hole) {
        ASSERT_TRUE(std::isfinite(fine.at(c, r))) << c << " " << r;
      }
    }
  }
  Heightfield same = coarse;
  upsample(same, 1, "objects.0.upsample");
  EXPECT_EQ(same.columns, coarse.columns);
  EXPECT_TRUE(same.notes.empty());
  for (int bad : {0, -2, kMostUpsample + 1}) {
    try {
      upsample(same, bad, "objects.0.upsample");
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("objects.0.upsample"), std::string::npos) << e.what();
    }
  }
}

// The factor a lone DEM gets: the least that gives its larger side the samples asked for,
// held to what fits in the mesh's vertices; none for a grid that has them.
TEST(Upsample, TheFactorReachesTheSidesAskedForWithinTheVertices) {
  const Heightfield coast = sampled(120, 91, 1.0);   // the BC coast's grid
  EXPECT_EQ(upsampleFactor(coast, 400, 250000), 4);  // 477 x 361
  EXPECT_EQ(upsampleFactor(coast, 400, 100000), 3);  // 357 x 271 = 96.7k; 4 x is over
  EXPECT_EQ(upsampleFactor(coast, 400, 90000), 2);
  EXPECT_EQ(upsampleFactor(sampled(468, 327, 1.0), 400, 250000), 1);
  EXPECT_EQ(upsampleFactor(sampled(20, 20, 1.0), 400, 1 << 28), kMostUpsample);
}

}  // namespace shanshui::terrain

namespace shanshui::terrain {

// Heights near the largest double (a corrupt or hostile file) overflow the cubic's sums; the
// new samples there fall back to straight lines between the cell's corners and stay finite.
TEST(Upsample, HeightsNearTheLargestDoubleStayFinite) {
  Heightfield h;
  h.columns = h.rows = 4;
  for (int i = 0; i < 16; ++i) h.elevation.push_back(i % 2 ? 1.7e308 : -1.7e308);
  upsample(h, 3, "test");
  for (double z : h.elevation) ASSERT_TRUE(std::isfinite(z)) << z;
}

}  // namespace shanshui::terrain
