// End-to-end: the real programs on real files, and what they write.
#include <fstream>

#include "shanshui/image/image_io.h"
#include "shanshui/mesh/mesh_io.h"
#include "test_support.h"

namespace shanshui {
namespace {

using test::quote;
using test::run;

std::string bin(const char* name) { return quote(test::binDir() / name); }
const std::filesystem::path kDem = test::sourceDir() / "samples/terrain/mount_st_helens.dem";

int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(Cli, EveryProgramHasHelpWithAnExample) {
  for (const char* p : {"shanshui-terrain", "shanshui-repair", "shanshui-render", "shanshui-view"}) {
    const auto r = run(bin(p) + " --help");
    EXPECT_EQ(r.exit_code, 0) << p;
    EXPECT_NE(r.output.find("Example"), std::string::npos) << p << ": " << r.output;
  }
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
  ASSERT_EQ(run(bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "m.ply") + " --max-vertices 5000").exit_code, 0);
  const std::string camera = " --size 200x150 --azimuth 30 --elevation 35";
  auto r = run("xvfb-run -a -s '-screen 0 640x480x24' " + bin("shanshui-view") + " " + quote(dir / "m.ply") + camera +
               " --frames 3 --screenshot " + quote(dir / "view.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run(bin("shanshui-render") + " " + quote(dir / "m.ply") + " -o " + quote(dir / "render.png") + camera);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const image::Image a = image::loadImage(dir / "view.png"), b = image::loadImage(dir / "render.png");
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  std::size_t differ = 0, nonPaper = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += std::abs(a.pixels[i] - b.pixels[i]) > 2.5f / 255;
  for (std::size_t i = 0; i < a.pixels.size(); i += 3) nonPaper += a.pixels[i] < 0.9f;
  EXPECT_LE(differ, a.pixels.size() / 1000) << "window and headless renders differ";
  EXPECT_GT(nonPaper, 100u) << "the screenshot shows no mountain";
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
      {bin("shanshui-terrain") + " " + quote(dir / "nodata.asc") + " -o " + quote(dir / "a.obj"), "nodata.asc", dir / "a.obj"},
      {bin("shanshui-terrain") + " " + quote(dir / "cut.dem") + " -o " + quote(dir / "keep.obj"), "cut.dem", dir / "keep.obj"},
      {bin("shanshui-terrain") + " " + quote(dir / "empty.png") + " -o " + quote(dir / "b.obj"), "empty.png", dir / "b.obj"},
      {bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "c.obj") + " --step 0", "--step", dir / "c.obj"},
      {bin("shanshui-terrain") + " " + quote(kDem) + " -o " + quote(dir / "c.obj") + " --cell-size 0", "--cell-size", dir / "c.obj"},
      {bin("shanshui-repair") + " " + quote(dir / "nofaces.off") + " -o " + quote(dir / "keep.obj"), "nofaces.off", dir / "keep.obj"},
      {bin("shanshui-render") + " " + quote(dir / "nofaces.off") + " -o " + quote(dir / "d.png"), "nofaces.off", dir / "d.png"},
      {bin("shanshui-render") + " " + quote(dir / "missing.obj") + " -o " + quote(dir / "d.png"), "missing.obj", dir / "d.png"},
      {bin("shanshui-render") + " " + quote(kDem) + " -o " + quote(dir / "d.png"), "unknown mesh format", dir / "d.png"},
      {bin("shanshui-render") + " " + quote(test::sourceDir() / "samples/terrain/none.obj") + " -o " + quote(dir / "d.png") +
           " --size 0x10", "--size", dir / "d.png"},
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

}  // namespace
}  // namespace shanshui
