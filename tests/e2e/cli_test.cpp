// End-to-end: the real programs on real files, and what they write.
#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <nlohmann/json.hpp>

#include "shanshui/image/image_io.h"
#include "shanshui/mesh/mesh_io.h"
#include "test_support.h"

namespace shanshui {
namespace {

using test::quote;
using test::run;

std::string bin(const char* name) {
  return quote(test::binDir() / name);
}
const std::filesystem::path kDem = test::sourceDir() / "samples/terrain/mount_st_helens.dem";

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(Cli, EveryProgramHasHelpWithAnExample) {
  for (const char* p : {"shanshui-terrain", "shanshui-repair", "shanshui-render", "shanshui-view", "shanshui-enhance",
                        "shanshui-quilt", "shanshui-param", "shanshui-demo"}) {
    const auto r = run(bin(p) + " --help");
    EXPECT_EQ(r.exit_code, 0) << p;
    EXPECT_NE(r.output.find("Example"), std::string::npos) << p << ": " << r.output;
  }
}

// Start-up cost is the shared libraries a program loads (issue 20: ~260 each cost ~0.3 s
// before anything ran). The dynamic loader lists them without running the program; the
// heavy ones stay out of the programs that do not use them (OpenImageIO is a module loaded
// on first use of another format; ximgproc drags in dnn and calib3d; only the programs
// that draw load GL).
TEST(Cli, EveryProgramLoadsOnlyTheLibrariesItUses) {
  const std::vector<std::string> never = {"OpenImageIO", "opencv_dnn", "opencv_ximgproc", "opencv_calib3d", "libboost"};
  const std::vector<std::string> gl = {"libepoxy", "libEGL", "libglfw"};
  for (const char* p : {"shanshui-terrain", "shanshui-repair", "shanshui-render", "shanshui-view", "shanshui-enhance",
                        "shanshui-quilt", "shanshui-param", "shanshui-demo"}) {
    const auto r = run("LD_TRACE_LOADED_OBJECTS=1 " + bin(p));
    ASSERT_EQ(r.exit_code, 0) << p;
    EXPECT_LE(lines(r.output), 45) << p << " loads:\n" << r.output;
    const std::string name = p;
    const bool draws = name == "shanshui-render" || name == "shanshui-view" || name == "shanshui-param";  // --checker
    for (const std::string& lib : never) EXPECT_EQ(r.output.find(lib), std::string::npos) << p << " loads " << lib;
    for (const std::string& lib : draws ? std::vector<std::string>{} : gl) {
      EXPECT_EQ(r.output.find(lib), std::string::npos) << p << " loads " << lib;
    }
  }
}

// --upsample: the sample hill (160 x 160 samples) twice as fine is 319 x 319 vertices, and
// says so.
TEST(Cli, TerrainUpsamplesACoarseGrid) {
  test::TempDir dir;
  const auto r = run(bin("shanshui-terrain") + " " + quote(test::sourceDir() / "samples/terrain/hill.asc") + " -o " +
                     quote(dir / "fine.obj") + " --upsample 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("made 2 times finer (319 x 319"), std::string::npos) << r.output;
  EXPECT_EQ(mesh::readPolygonSoup(dir / "fine.obj").positions.size(), 319u * 319u);
}

// --smooth-steps: the sample hill stores tenths; smoothed within them, every vertex stays
// within 0.05 m of the height the plain mesh has, and some move.
TEST(Cli, TerrainSmoothsHeightsStoredInSteps) {
  test::TempDir dir;
  const std::string base = bin("shanshui-terrain") + " " + quote(test::sourceDir() / "samples/terrain/hill.asc");
  auto r = run(base + " -o " + quote(dir / "plain.obj"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("smoothed within half a step"), std::string::npos) << r.output;
  r = run(base + " -o " + quote(dir / "smooth.obj") + " --smooth-steps");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("steps of 0.1 m smoothed within half a step"), std::string::npos) << r.output;
  const mesh::PolygonSoup plain = mesh::readPolygonSoup(dir / "plain.obj"),
                          smooth = mesh::readPolygonSoup(dir / "smooth.obj");
  ASSERT_EQ(plain.positions.size(), smooth.positions.size());
  double worst = 0.0, moved = 0.0;
  for (std::size_t i = 0; i < plain.positions.size(); ++i) {
    const double d = std::abs(plain.positions[i].z - smooth.positions[i].z);
    worst = std::max(worst, d);
    moved += d > 1e-3 ? 1.0 : 0.0;
  }
  EXPECT_LE(worst, 0.05 + 1e-6);
  EXPECT_GT(moved, 0.1 * static_cast<double>(plain.positions.size()));
}

// --subdivide: the sample hill's mesh at every 16th sample (10 x 10) Loop-subdivided twice
// is 37 x 37 vertices, and the report says so.
TEST(Cli, RepairSubdividesALowPolyLand) {
  test::TempDir dir;
  auto r = run(bin("shanshui-terrain") + " " + quote(test::sourceDir() / "samples/terrain/hill.asc") + " -o " +
               quote(dir / "low.obj") + " --step 16");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run(bin("shanshui-repair") + " " + quote(dir / "low.obj") + " -o " + quote(dir / "round.obj") +
          " --subdivide 2 --report " + quote(dir / "r.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(mesh::readPolygonSoup(dir / "round.obj").positions.size(), 37u * 37u);
  std::ifstream in(dir / "r.json");
  const std::string report((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(report.find("\"subdivided\""), std::string::npos) << report;
}

TEST(Cli, DemToMeshToHeadlessRender) {
  test::TempDir dir;
  auto r = run(bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "msh.obj") + " --max-vertices 20000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("682.0 to 2543.0"), std::string::npos) << r.output;
  const mesh::PolygonSoup soup = mesh::readPolygonSoup(dir / "msh.obj");
  EXPECT_LE(soup.positions.size(), 20000u);
  EXPECT_GT(soup.faces.size(), 10000u);

  r = run(bin("shanshui-render") + " " + quote(dir / "msh.obj") + " -o " + quote(dir / "msh.png") + " --size 320x200");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const image::Image img = image::loadImage(dir / "msh.png");
  EXPECT_EQ(img.width, 320);
  EXPECT_EQ(img.height, 200);
  // The mountain is there: a good share of ink-toned pixels, darker than the paper.
  std::size_t ink = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) ink += img.at(x, y, 0) < 0.85f;
  EXPECT_GT(ink, img.pixels.size() / 3 / 50);
}

TEST(Cli, ViewerScreenshotUnderXvfbMatchesHeadlessRender) {
  if (run("command -v xvfb-run").exit_code != 0) GTEST_SKIP() << "xvfb-run is not installed";
  test::TempDir dir;
  // The sample scene (lines, shading, wrinkles), a lighter mesh, a scripted camera: the
  // viewer turns 10 degrees per frame, so after 3 frames it looks from azimuth 30 + 30.
  const std::string common = quote(test::sourceDir() / "samples/scenes/default.json") +
                             " --size 240x180 --set objects.0.max_vertices=20000 --set camera.elevation=35";
  auto r = run("xvfb-run -a -s '-screen 0 640x480x24' " + bin("shanshui-view") + " " + common +
               " --set camera.azimuth=30 --orbit 10 --frames 3 --screenshot " + quote(dir / "view.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 frames at 240x180 in"), std::string::npos) << "no frame rate reported: " << r.output;
  r = run(bin("shanshui-render") + " " + common + " --set camera.azimuth=60 -o " + quote(dir / "render.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const image::Image a = image::loadImage(dir / "view.png"), b = image::loadImage(dir / "render.png");
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  std::size_t differ = 0, nonPaper = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += std::abs(a.pixels[i] - b.pixels[i]) > 2.5f / 255;
  for (std::size_t i = 0; i < a.pixels.size(); i += 3) nonPaper += a.pixels[i] < 0.8f;
  EXPECT_LE(differ, a.pixels.size() / 1000) << "window and headless renders differ";
  EXPECT_GT(nonPaper, a.pixels.size() / 3 / 20) << "the screenshot shows no mountain";
}

// The viewer's panel says in red when the frame had no room for some tree and dot marks
// (the room lowered with SHANSHUI_ELEMENT_MARKS), and shows no red otherwise.
TEST(Cli, ViewerPanelWarnsOfMarksWithoutRoom) {
  if (run("command -v xvfb-run").exit_code != 0) GTEST_SKIP() << "xvfb-run is not installed";
  test::TempDir dir;
  auto redPixels = [&](const std::string& env, const char* name) {
    const auto r = run(env + "xvfb-run -a -s '-screen 0 640x480x24' " + bin("shanshui-view") + " " +
                       quote(test::sourceDir() / "samples/scenes/grove.json") +
                       " --size 480x360 --set objects.0.max_vertices=20000 --frames 2 --screenshot-ui --screenshot " +
                       quote(dir / name));
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const image::Image img = image::loadImage(dir / name);
    int red = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        red += img.at(x, y, 0) > 0.8f && img.at(x, y, 1) < 0.45f && img.at(x, y, 2) < 0.4f;
    return red;
  };
  EXPECT_GT(redPixels("SHANSHUI_ELEMENT_MARKS=10 ", "few.png"), 200) << "the warning's text";
  EXPECT_EQ(redPixels("", "all.png"), 0);
}

TEST(Cli, BadInputGivesOneLineNamingTheFileAndWritesNothing) {
  test::TempDir dir;
  std::ofstream(dir / "nodata.asc") << "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n"
                                       "NODATA_value -9999\n-9999 -9999\n-9999 -9999\n";
  std::ofstream(dir / "cut.dem") << "truncated";
  std::ofstream(dir / "empty.png").close();
  std::ofstream(dir / "nofaces.off") << "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n";
  std::ofstream(dir / "keep.obj") << "precious";
  struct Case {
    std::string command;
    std::string file;
    std::filesystem::path output;
  };
  const Case cases[] = {
      {bin("shanshui-terrain") + " " + quote(dir / "nodata.asc") + " -o " + quote(dir / "a.obj"), "nodata.asc",
       dir / "a.obj"},
      {bin("shanshui-terrain") + " " + quote(dir / "cut.dem") + " -o " + quote(dir / "keep.obj"), "cut.dem",
       dir / "keep.obj"},
      {bin("shanshui-terrain") + " " + quote(dir / "empty.png") + " -o " + quote(dir / "b.obj"), "empty.png",
       dir / "b.obj"},
      {bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "c.obj") + " --step 0", "--step",
       dir / "c.obj"},
      {bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "c.obj") + " --cell-size 0", "--cell-size",
       dir / "c.obj"},
      {bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "c.obj") + " --upsample 9", "--upsample",
       dir / "c.obj"},
      {bin("shanshui-repair") + " " + quote(dir / "nofaces.off") + " -o " + quote(dir / "keep.obj") + " --subdivide 5",
       "--subdivide", dir / "keep.obj"},
      {bin("shanshui-repair") + " " + quote(dir / "nofaces.off") + " -o " + quote(dir / "keep.obj"), "nofaces.off",
       dir / "keep.obj"},
      {bin("shanshui-render") + " " + quote(dir / "nofaces.off") + " -o " + quote(dir / "d.png"), "nofaces.off",
       dir / "d.png"},
      {bin("shanshui-render") + " " + quote(dir / "missing.obj") + " -o " + quote(dir / "d.png"), "missing.obj",
       dir / "d.png"},
      {bin("shanshui-render") + " " + quote(dir / "cut.txt") + " -o " + quote(dir / "d.png"), "cut.txt", dir / "d.png"},
      {bin("shanshui-render") + " " + quote(test::sourceDir() / "samples/terrain/none.obj") + " -o " +
           quote(dir / "d.png") + " --size 0x10",
       "--size", dir / "d.png"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.command);
    const auto r = run(c.command);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.file), std::string::npos) << r.output;
    if (c.output.filename() == "keep.obj") {
      std::ifstream in(c.output);
      std::string kept;
      in >> kept;
      EXPECT_EQ(kept, "precious");
    } else {
      EXPECT_FALSE(std::filesystem::exists(c.output));
    }
  }
  // Nothing half-written lies around either.
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
}

std::string readBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Cli, EnhanceThenQuiltATileableTexture) {
  std::filesystem::path scan = test::sharedData() / "textures/ink_hemp_fiber.png";
  if (!std::filesystem::exists(scan)) scan = test::sourceDir() / "samples/textures/rain_strokes_scan.png";
  test::TempDir dir;
  auto r = run(bin("shanshui-enhance") + " " + quote(scan) + " -o " + quote(dir / "sample.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("(percentiles)"), std::string::npos) << r.output;
  image::ImageInfo info;
  const image::Image sample = image::loadImage(dir / "sample.png", &info);
  EXPECT_EQ(info.depth, image::PixelDepth::UInt8) << "the input's depth by default";
  const auto [lo, hi] = std::minmax_element(sample.pixels.begin(), sample.pixels.end());
  EXPECT_EQ(*lo, 0.0f);
  EXPECT_EQ(*hi, 1.0f);

  const std::string quilt =
      bin("shanshui-quilt") + " " + quote(dir / "sample.png") + " --size 300x200 --block 40 --tileable --seed 9";
  r = run(quilt + " -o " + quote(dir / "a.png") + " --threads 1 --report " + quote(dir / "a.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run(quilt + " -o " + quote(dir / "b.png") + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(readBytes(dir / "a.png"), readBytes(dir / "b.png")) << "output depends on the thread count";
  const image::Image texture = image::loadImage(dir / "a.png");
  EXPECT_EQ(texture.width, 300);
  EXPECT_EQ(texture.height, 200);

  const auto report = nlohmann::json::parse(readBytes(dir / "a.json"));
  for (const char* key : {"seconds", "blocks", "mean_seam_error_per_overlap_pixel", "coherence", "source_usage",
                          "verbatim_copy_ratio", "wrap_seam_error", "options"}) {
    EXPECT_TRUE(report.contains(key)) << key;
  }
  EXPECT_EQ(report["options"]["threads"], 1);
  EXPECT_EQ(report["options"]["tileable"], true);
  EXPECT_GT(report["blocks"].get<int>(), 20);
  EXPECT_GE(report["coherence"]["mean"].get<double>(), 0.0);
}

TEST(Cli, TextureToolsRefuseBadInputAndWriteNothing) {
  std::filesystem::path scan = test::sharedData() / "textures/ink_dabs.png";  // 180x128
  if (!std::filesystem::exists(scan)) scan = test::sourceDir() / "samples/textures/rain_strokes_scan.png";
  const image::Image scanned = image::loadImage(scan);
  const std::string too_big = std::to_string(std::min(scanned.width, scanned.height) + 1);
  test::TempDir dir;
  image::saveImage(image::Image(32, 32, 1, 0.4f), dir / "flat.png");
  {  // An image whose only channel is alpha.
    auto out = OIIO::ImageOutput::create((dir / "mask.exr").string());
    OIIO::ImageSpec spec(16, 16, 1, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"A"};
    spec.alpha_channel = 0;
    std::vector<float> zeros(256, 0.5f);
    ASSERT_TRUE(out && out->open((dir / "mask.exr").string(), spec));
    out->write_image(OIIO::TypeDesc::FLOAT, zeros.data());
    out->close();
  }
  std::ofstream(dir / "keep.png") << "precious";
  std::ofstream(dir / "broken.png") << "not a png";
  const std::string enhance = bin("shanshui-enhance") + " ";
  const std::string quilt = bin("shanshui-quilt") + " " + quote(scan) + " --size 200x200 ";
  struct Case {
    std::string command;
    std::string names;  // what the message must say
  };
  const std::string keep = " -o " + quote(dir / "keep.png");
  const Case cases[] = {
      {enhance + quote(scan) + keep + " --range 0.6:0.4", "0.6:0.4; b must be greater than a"},
      {enhance + quote(scan) + keep + " --range 0.2", "--range: '0.2' is not a pair"},
      {enhance + quote(scan) + keep + " --to 0.5:0.5", "c and d must differ"},
      {enhance + quote(scan) + keep + " --auto 90:10", "percentiles 90:10"},
      {enhance + quote(dir / "flat.png") + keep, "flat.png: no contrast"},
      {enhance + quote(dir / "mask.exr") + keep, "mask.exr: the image has only an alpha channel"},
      {enhance + quote(dir / "broken.png") + keep, "broken.png"},
      {enhance + quote(dir / "missing.png") + keep, "missing.png: no such file"},
      {quilt + keep + " --block 2", "block 2; expected at least 3"},
      {quilt + keep + " --block " + too_big, "smaller than block " + too_big},
      {quilt + keep + " --block 24 --overlap 24", "overlap 24; expected 1 <= overlap < block"},
      {quilt + keep + " --block 24 --overlap 0", "--overlap: 0 is out of range"},
      {bin("shanshui-quilt") + " " + quote(scan) + keep + " --size 20x300",
       "output size 20x300 is smaller than block 48"},
      {quilt + keep + " --tolerance -1", "tolerance -1"},
      {bin("shanshui-quilt") + " " + quote(dir / "mask.exr") + keep + " --size 64x64 --block 8",
       "only an alpha channel"},
      {bin("shanshui-quilt") + " " + quote(dir / "broken.png") + keep + " --size 64x64", "broken.png"},
      {quilt + keep + " --report " + quote(dir / "no/such/dir/r.json"), "output directory does not exist"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.command);
    const auto r = run(c.command);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(c.names), std::string::npos) << r.output;
    EXPECT_EQ(readBytes(dir / "keep.png"), "precious");
  }
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
}

TEST(Cli, ParamGivesUvsReportAndCheckerView) {
  test::TempDir dir;
  auto r = run(bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "m.obj") + " --max-vertices 20000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run(bin("shanshui-param") + " " + quote(dir / "m.obj") + " -o " + quote(dir / "uv.obj") +
          " --texel-size 500 --report " + quote(dir / "p.json") + " --checker " + quote(dir / "c.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const mesh::PolygonSoup soup = mesh::readPolygonSoup(dir / "uv.obj");
  ASSERT_EQ(soup.uvs.size(), soup.positions.size());
  // One texture repeat per 500 m: the UVs span about the DEM's extent (~10 km) / 500.
  float maxU = 0;
  for (const glm::vec2& uv : soup.uvs) maxU = std::max(maxU, uv.x);
  EXPECT_GT(maxU, 10.0f);
  EXPECT_LT(maxU, 40.0f);
  const auto report = nlohmann::json::parse(readBytes(dir / "p.json"));
  EXPECT_EQ(report["valid"], true);
  EXPECT_EQ(report["distortion"]["flipped"], 0);
  EXPECT_LE(report["distortion"]["l2_stretch"].get<double>(), 1.05);
  EXPECT_TRUE(report.contains("trials"));
  EXPECT_TRUE(report.contains("repair"));
  const image::Image checker = image::loadImage(dir / "c.png");
  // The checkerboard shows: many pixels darkened by the dark squares, many not.
  std::size_t dark = 0, light = 0;
  for (std::size_t i = 0; i < checker.pixels.size(); i += 3) {
    dark += checker.pixels[i] < 0.6f;
    light += checker.pixels[i] > 0.8f;
  }
  EXPECT_GT(dark, checker.pixels.size() / 3 / 50);
  EXPECT_GT(light, checker.pixels.size() / 3 / 50);
}

// A closed animal: auto prints what it tried and why it kept the atlas, and the report
// lists the charts.
TEST(Cli, ParamChartsAClosedMeshAndSaysWhy) {
  test::TempDir dir;
  const std::filesystem::path cow = test::cgalMeshes() / "cow.off";
  SHANSHUI_REQUIRE_FILE(cow);
  const auto r = run(bin("shanshui-param") + " " + quote(cow) + " -o " + quote(dir / "uv.obj") + " --report " +
                     quote(dir / "p.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("auto tried"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("kept charts"), std::string::npos) << r.output;
  const auto report = nlohmann::json::parse(readBytes(dir / "p.json"));
  EXPECT_EQ(report["method"], "charts");
  EXPECT_EQ(report["atlas"]["per_chart"].size(), report["atlas"]["charts"].get<std::size_t>());
  EXPECT_LE(report["distortion"]["l2_stretch"].get<double>(), 1.5);
  // The budget left goes to ARAP rounds from the best one-piece map; they fold this one,
  // so the atlas stays. On a loaded machine the trials can spend the whole budget and no
  // round runs (the report then has none; reading the missing key of a const json was
  // undefined and failed about one run in five under load). --no-refine leaves them out.
  if (report.contains("refinements")) {
    ASSERT_EQ(report["refinements"].size(), 1u) << report.dump(1);
    EXPECT_EQ(report["refinements"][0]["kept"], false);
    EXPECT_NE(r.output.find("refine (ARAP rounds from"), std::string::npos) << r.output;
  }
  const auto plain = run(bin("shanshui-param") + " " + quote(cow) + " -o " + quote(dir / "plain.obj") + " --report " +
                         quote(dir / "plain.json") + " --no-refine");
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_FALSE(nlohmann::json::parse(readBytes(dir / "plain.json")).contains("refinements"));
  EXPECT_EQ(plain.output.find("refine ("), std::string::npos) << plain.output;
  // One seam cut open: L2 in the hundreds, refused (after the repair's line), nothing written.
  const auto refused =
      run(bin("shanshui-param") + " " + quote(cow) + " -o " + quote(dir / "bad.obj") + " --method tutte");
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.output.find("above --max-stretch 2"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("--accept-stretch"), std::string::npos) << refused.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.obj"));
  // The seams are split vertices: the OBJ reads back with more vertices than the cow.
  const mesh::PolygonSoup soup = mesh::readPolygonSoup(dir / "uv.obj");
  EXPECT_EQ(soup.uvs.size(), soup.positions.size());
  EXPECT_GT(soup.positions.size(), 2904u);
  // The renderer keeps the atlas's UVs through its repair (the seams' coincident vertices).
  const auto drawn =
      run(bin("shanshui-render") + " " + quote(dir / "uv.obj") + " -o " + quote(dir / "cow.png") +
          " --size 160x120 --set objects.0.wrinkle.texture=" +
          quote("\"" + (test::sourceDir() / "samples/textures/rain_strokes_wrinkle.png").string() + "\""));
  EXPECT_EQ(drawn.exit_code, 0) << drawn.output;
}

// Three fins on one edge (a non-manifold edge) and a separate tetrahedron: repaired, every
// component kept, charted; never refused as "not a disc".
TEST(Cli, ParamChartsNonManifoldAndSeveralComponents) {
  test::TempDir dir;
  std::ofstream(dir / "fins.obj") << "v 0 0 0\nv 0 0 1\nv 1 0 0.5\nv -0.5 0.87 0.5\nv -0.5 -0.87 0.5\n"
                                     "v 3 0 0\nv 4 0 0\nv 3 1 0\nv 3 0 1\n"
                                     "f 1 2 3\nf 1 2 4\nf 1 2 5\nf 6 8 7\nf 6 7 9\nf 7 8 9\nf 8 6 9\n";
  const auto r = run(bin("shanshui-param") + " " + quote(dir / "fins.obj") + " -o " + quote(dir / "uv.obj") +
                     " --report " + quote(dir / "p.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto report = nlohmann::json::parse(readBytes(dir / "p.json"));
  EXPECT_EQ(report["method"], "charts");
  EXPECT_EQ(report["valid"], true);
  EXPECT_EQ(report["faces"], 7);  // nothing dropped
  EXPECT_GE(report["atlas"]["charts"].get<int>(), 2);
}

TEST(Cli, ParamRefusesWhatItCannotFlattenAndWritesNothing) {
  test::TempDir dir;
  const std::filesystem::path bear = test::cgalMeshes() / "anchor.off";  // closed, genus 4
  SHANSHUI_REQUIRE_FILE(bear);
  std::ofstream(dir / "keep.obj") << "precious";
  std::ofstream(dir / "nan.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n";
  const std::string keep = " -o " + quote(dir / "keep.obj");
  const std::string param = bin("shanshui-param") + " ";
  const std::filesystem::path cow = test::cgalMeshes() / "cow.off";  // one seam: L2 in the hundreds
  const std::pair<std::string, std::string> cases[] = {
      {param + quote(bear) + keep + " --method lscm", "closed mesh of genus 4"},
      {param + quote(cow) + keep + " --method charts --padding 100", "--padding"},
      {param + quote(cow) + keep + " --budget -1", "--budget"},
      {param + quote(cow) + keep + " --texel-size 1e-300", "--texel-size: 1e-300 makes UVs beyond a float's range"},
      {param + quote(kDem) + keep, "not a mesh format shanshui reads by its extension '.dem'"},
      {param + quote(dir / "nan.off") + keep, "nan.off"},
      {param + quote(bear) + keep + " --method magic", "unknown method 'magic'"},
      {param + quote(bear) + keep + " --border hexagon", "unknown border 'hexagon'"},
      {param + quote(bear) + " -o " + quote(dir / "out.ply"), "UVs are only written to .obj"},
      {param + quote(bear) + keep + " --texel-size -3", "--texel-size: -3"},
  };
  for (const auto& [command, names] : cases) {
    SCOPED_TRACE(command);
    const auto r = run(command);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(names), std::string::npos) << r.output;
    EXPECT_EQ(readBytes(dir / "keep.obj"), "precious");
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out.ply"));
}

}  // namespace
}  // namespace shanshui

namespace shanshui {
namespace {

// Which stages a demo run ran ("name running ...") and which it reused.
std::map<std::string, std::string> demoStages(const std::string& output) {
  std::map<std::string, std::string> stages;
  std::istringstream in(output);
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string name, what;
    words >> name >> what;
    if (what == "running" || what == "reused") stages[name] = what;
  }
  return stages;
}

TEST(Cli, DemoRunsTheChainThenReusesWhatIsUpToDate) {
  test::TempDir dir;
  const std::filesystem::path samples = dir / "samples", out = dir / "out";
  for (const char* f : {"textures/rain_strokes_scan.png",
                        "textures/rain_strokes_wrinkle.png",
                        "terrain/mount_st_helens.dem",
                        "scenes/default.json",
                        "scenes/high_distance.json",
                        "scenes/deep_distance.json",
                        "scenes/level_distance.json",
                        "scenes/light_colour.json",
                        "scenes/moving_boat.json",
                        "meshes/fishing_boat.obj",
                        "scenes/grove.json",
                        "terrain/hill.asc",
                        "scenes/lake.json",
                        "scenes/painting.json",
                        "meshes/pagoda.obj",
                        "meshes/pavilion.obj",
                        "meshes/hut.obj",
                        "meshes/boulder_a.obj",
                        "meshes/boulder_b.obj",
                        "meshes/boulder_c.obj"}) {
    std::filesystem::create_directories((samples / f).parent_path());
    std::filesystem::copy_file(test::sourceDir() / "samples" / f, samples / f);
  }
  // Relative paths, as `make demo` gives them.
  const std::string demo =
      "cd " + quote(dir.path()) + " && " + bin("shanshui-demo") + " --quick --frames 2 --samples samples --out out";
  auto r = run(demo);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::map<std::string, std::string> all_ran = {{"enhance", "running"},       {"quilt", "running"},
                                                      {"terrain", "running"},       {"param", "running"},
                                                      {"painting", "running"},      {"still", "running"},
                                                      {"orbit", "running"},         {"high_distance", "running"},
                                                      {"deep_distance", "running"}, {"level_distance", "running"},
                                                      {"grove", "running"},         {"lake", "running"},
                                                      {"level_strokes", "running"}, {"light_colour", "running"},
                                                      {"moving_boat", "running"},   {"moving_boat_sharp", "running"},
                                                      {"boat_lines", "running"},    {"boat_strokes", "running"},
                                                      {"stability", "running"}};
  EXPECT_EQ(demoStages(r.output), all_ran);
  for (const char* f : {"report.md", "painting.png", "mountain.png", "orbit_0000.png", "orbit_0001.png",
                        "assets/wrinkle.png", "assets/st_helens_uv.obj", "assets/checker.png", "assets/scan.png"}) {
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  }
  const std::string report = readBytes(out / "report.md");
  EXPECT_NE(report.find("![mountain](mountain.png)"), std::string::npos);
  EXPECT_LT(report.find("![painting](painting.png)"), report.find("![mountain](mountain.png)")) << "the headline";
  EXPECT_NE(report.find("| painting | 0."), std::string::npos);
  EXPECT_NE(report.find("![high](high.png) ![deep](deep.png) ![level](level.png)"), std::string::npos);
  EXPECT_NE(report.find("| deep | 0."), std::string::npos) << "the look statistics of each picture";
  EXPECT_NE(report.find("![grove](grove.png)"), std::string::npos);
  EXPECT_NE(report.find("| grove | 0."), std::string::npos) << "the grove's look, marks per megapixel among them";
  EXPECT_NE(report.find("![lake](lake.png)"), std::string::npos);
  EXPECT_NE(report.find("| lake | 0."), std::string::npos);
  EXPECT_NE(report.find("![level strokes](level_strokes.png)"), std::string::npos);
  EXPECT_NE(report.find("| level_strokes | 0."), std::string::npos);
  EXPECT_NE(report.find("![light colour](light_colour.png)"), std::string::npos);
  EXPECT_NE(report.find("| light_colour | 0."), std::string::npos);
  EXPECT_NE(report.find("![moving 2](moving_0002.png)"), std::string::npos);
  EXPECT_NE(report.find("![boat strokes](boat_strokes.png)"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out / "boat_strokes.png"));
  EXPECT_TRUE(std::filesystem::exists(out / "moving_0002.png"));
  EXPECT_TRUE(std::filesystem::exists(out / "moving_sharp_0002.png"));
  EXPECT_NE(report.find("L2 stretch"), std::string::npos);
  EXPECT_EQ(report.find(dir.path().string()), std::string::npos) << "the report's links are relative";
  // The stability table of this run (its fast cases with --quick), on a fresh machine too.
  EXPECT_NE(report.find("| curvature | a single triangle | finite result"), std::string::npos) << report;
  EXPECT_TRUE(std::filesystem::exists(out / "stability/stability.csv"));

  // Nothing changed: every stage is reused. A copied asset left empty (a run killed by an
  // older demo) is written again, not refused as an empty input.
  std::ofstream(out / "assets/scan.png", std::ios::trunc).close();
  r = run(demo);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const auto& [name, what] : demoStages(r.output)) EXPECT_EQ(what, "reused") << name;
  EXPECT_EQ(readBytes(out / "assets/scan.png"), readBytes(samples / "textures/rain_strokes_scan.png"));

  // A new scan: its texture stages and the paintings run again, the mesh stages do not.
  image::Image scan = image::loadImage(samples / "textures/rain_strokes_scan.png");
  for (int x = 0; x < scan.width; ++x) scan.at(x, 0, 0) = 1.0f - scan.at(x, 0, 0);
  image::saveImage(scan, samples / "textures/rain_strokes_scan.png");
  r = run(demo);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(demoStages(r.output), (std::map<std::string, std::string>{{"enhance", "running"},
                                                                      {"quilt", "running"},
                                                                      {"terrain", "reused"},
                                                                      {"param", "reused"},
                                                                      {"painting", "running"},
                                                                      {"still", "running"},
                                                                      {"orbit", "running"},
                                                                      {"high_distance", "reused"},
                                                                      {"deep_distance", "reused"},
                                                                      {"level_distance", "reused"},
                                                                      {"grove", "reused"},
                                                                      {"lake", "reused"},
                                                                      {"level_strokes", "reused"},
                                                                      {"light_colour", "reused"},
                                                                      {"moving_boat", "reused"},
                                                                      {"moving_boat_sharp", "reused"},
                                                                      {"boat_lines", "reused"},
                                                                      {"boat_strokes", "reused"},
                                                                      {"stability", "reused"}}));

  // A reference picture goes beside the paintings; a missing one is named before any work.
  r = run(demo + " --reference samples/textures/rain_strokes_scan.png");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(readBytes(out / "report.md").find("![reference](assets/reference.png)"), std::string::npos);
  r = run(demo + " --reference nowhere.jpg");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("--reference: nowhere.jpg: not found"), std::string::npos) << r.output;

  // A broken sample scene is named, with where its text breaks, before any stage runs.
  std::ofstream(samples / "scenes/painting.json") << "{ broken";
  r = run(demo + " --force");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("painting.json: not valid JSON: parse error at line 1"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("running"), std::string::npos) << r.output;

  // A missing sample is named.
  std::filesystem::remove(samples / "terrain/mount_st_helens.dem");
  r = run(demo);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("mount_st_helens.dem: not found"), std::string::npos) << r.output;
}

// A failing stability suite still leaves the report, with its table and the failure, and
// fails the demo. The programs are copied beside a stand-in suite that records one case and
// fails.
TEST(Cli, DemoWithAFailingStabilitySuiteWritesTheReportThenFails) {
  test::TempDir dir;
  const std::filesystem::path bin_dir = dir / "bin";
  std::filesystem::create_directories(bin_dir);
  for (const char* p : {"shanshui-demo", "shanshui-enhance", "shanshui-quilt", "shanshui-terrain", "shanshui-param",
                        "shanshui-render", "shanshui-repair"})
    std::filesystem::copy_file(test::binDir() / p, bin_dir / p);
  std::ofstream(bin_dir / "test_stability")
      << "#!/bin/sh\nprintf '# Stability suite\\n\\n| stage | case | outcome |\\n|---|---|---|\\n"
         "| fake | stand-in case | NaN written |\\n' > \"$SHANSHUI_STABILITY_DIR/stability.md\"\n"
         "echo '[  FAILED  ] 1 test'\nexit 1\n";
  std::filesystem::permissions(bin_dir / "test_stability", std::filesystem::perms::owner_all);
  const auto r = run(quote(bin_dir / "shanshui-demo") + " --quick --frames 1 --samples " +
                     quote(test::sourceDir() / "samples") + " --out " + quote(dir / "out"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("stage stability failed: [  FAILED  ] 1 test"), std::string::npos) << r.output;
  const std::string report = readBytes(dir / "out/report.md");
  EXPECT_NE(report.find("| fake | stand-in case | NaN written |"), std::string::npos) << report;
  EXPECT_NE(report.find("FAILED"), std::string::npos) << report;
  EXPECT_TRUE(std::filesystem::exists(dir / "out/mountain.png"));
}

}  // namespace
}  // namespace shanshui
