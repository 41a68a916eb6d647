// shanshui-bench: the driver runs the stages' sweeps, reads their points files and draws
// the plots; its axis choice is checked on its own.
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "plot.h"  // apps/bench
#include "shanshui/image/image_io.h"
#include "test_support.h"

namespace shanshui {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Distinct colours in a picture (a plot with series has several besides white, black, grey).
std::size_t colours(const image::Image& img) {
  std::set<int> seen;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const int r = static_cast<int>(img.at(x, y, 0) * 255), g = static_cast<int>(img.at(x, y, 1) * 255),
                b = static_cast<int>(img.at(x, y, 2) * 255);
      if (r != g || g != b) seen.insert((r << 16) | (g << 8) | b);  // saturated: series colours
    }
  return seen.size();
}

TEST(BenchPlot, AxisIsLogarithmicOnlyForPositiveValuesSpanningMoreThanAFactorOf20) {
  const bench::Axis log = bench::chooseAxis({3.0, 0.02, 450.0, std::nan("")});
  EXPECT_TRUE(log.log);
  EXPECT_EQ(log.lo, -2.0);
  EXPECT_EQ(log.hi, 3.0);
  EXPECT_EQ(log.ticks.front(), 0.01);
  EXPECT_EQ(log.ticks.back(), 1000.0);
  EXPECT_NEAR(log.map(0.1), 0.2, 1e-12);

  for (const std::vector<double>& v :
       {std::vector<double>{0.0, 5.0}, std::vector<double>{2.0, 3.0}, std::vector<double>{-1.0, 100.0},
        std::vector<double>{7.0}, std::vector<double>{}}) {
    const bench::Axis a = bench::chooseAxis(v);
    EXPECT_FALSE(a.log);
    ASSERT_GE(a.ticks.size(), 2u);
    for (double x : v) {  // every value inside the drawn range
      EXPECT_GE(a.map(x), 0.0);
      EXPECT_LE(a.map(x), 1.0);
    }
    for (std::size_t i = 1; i < a.ticks.size(); ++i) EXPECT_GT(a.ticks[i], a.ticks[i - 1]);
  }
}

TEST(BenchPlot, WritesSeriesOrANoDataPlotAndNamesAnUnwritableFile) {
  const test::TempDir dir;
  bench::Plot p{
      "t", "run time (ms)", "error", {{"a", {1, 10, 100}, {0.1, 0.01, 0.001}, true}, {"b", {2}, {0.5}, false}}};
  bench::writePlot(p, dir / "p.png");
  EXPECT_GE(colours(image::loadImage(dir / "p.png")), 2u);
  bench::Plot empty{"t", "x", "y", {{"nan", {std::nan("")}, {1.0}, true}}};
  bench::writePlot(empty, dir / "empty.png");
  EXPECT_TRUE(fs::exists(dir / "empty.png"));
  test::expectErrorNaming([&] { bench::writePlot(p, dir / "no/such/dir/p.png"); }, "no/such/dir", "");
}

// Every stage's quick sweep (about a minute here): this is what caught the canvas bench
// reading past its frames when the paths are short.
TEST(BenchCli, QuickStagesWriteTablesPointsAndPlots) {
  const test::TempDir dir;
  const auto r = test::run(test::quote(test::binDir() / "shanshui-bench") + " --stage all --quick --out " +
                           test::quote(dir.path()));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string index = readText(dir / "README.md");
  const char* programs[] = {"quilt",     "param",   "curvature", "dequantize", "upsample", "ink",
                            "diffusion", "strokes", "paper",     "canvas",     "pipeline"};
  for (const char* program : programs) {
    EXPECT_NE(index.find(std::string("| bench_") + program + "_tradeoff |"), std::string::npos) << program;
  }
  EXPECT_EQ(index.find("failed"), std::string::npos) << index;
  // Every points file has finite, positive times and finite, non-negative errors.
  int points = 0;
  for (const char* program : programs) {
    const std::string f = std::string(program) + "_tradeoff_points.csv";
    std::ifstream in(dir / f);
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, "plot,y_label,series,joined,ms,error") << f;
    while (std::getline(in, line)) {
      const std::size_t c2 = line.rfind(','), c1 = line.rfind(',', c2 - 1);
      const double ms = std::stod(line.substr(c1 + 1, c2 - c1 - 1)), error = std::stod(line.substr(c2 + 1));
      EXPECT_TRUE(std::isfinite(ms) && ms > 0) << f << ": " << line;
      EXPECT_TRUE(std::isfinite(error) && error >= 0) << f << ": " << line;
      ++points;
    }
  }
  EXPECT_GE(points, 60);
  // The plots the index shows exist and have series drawn in colour.
  int plots = 0;
  for (std::size_t at = index.find("]("); at != std::string::npos; at = index.find("](", at + 2)) {
    const std::string target = index.substr(at + 2, index.find(')', at) - at - 2);
    if (target.size() < 4 || target.substr(target.size() - 4) != ".png") continue;
    ASSERT_TRUE(fs::exists(dir / target)) << target;
    EXPECT_GE(colours(image::loadImage(dir / target)), 3u) << target;
    ++plots;
  }
  // quilt 2, param 2 (the developable ridge, the charts of a cube), curvature 6 (object space, per pixel, the CDF, the
  // wrinkle filter, heights stored in steps, coarse grids made finer), diffusion 2, canvas 5 (N′: spectrum and
  // Gaussianity; tiles: spectrum and warping against patch; the mottle against its cell), strokes 2 (spline sampling,
  // linking), paper 2 (edge taps, shadow map), pipeline 1; and the pictures.
  EXPECT_EQ(plots, 22) << index;
  EXPECT_GE(colours(image::loadImage(dir / "canvas_dolly.png")), 3u);
  EXPECT_TRUE(fs::exists(dir / "pipeline_presets.png"));

  // Running one stage again into the same directory keeps the others in the index.
  const auto again = test::run(test::quote(test::binDir() / "shanshui-bench") + " --stage diffusion --quick --out " +
                               test::quote(dir.path()));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  const std::string index2 = readText(dir / "README.md");
  EXPECT_NE(index2.find("| curvature | bench_curvature_tradeoff | — | *earlier* |"), std::string::npos) << index2;
  EXPECT_NE(index2.find("| diffusion | bench_diffusion_tradeoff |"), std::string::npos) << index2;
  EXPECT_NE(index2.find("ink_tradeoff_curvature_per_pixel.png"), std::string::npos) << index2;
}

TEST(BenchCli, AFailingProgramIsReportedAndTheOthersStillRun) {
  const test::TempDir dir;
  fs::create_directories(dir / "curvature_tradeoff_points.csv");  // the curvature bench cannot write its points
  const auto r = test::run(test::quote(test::binDir() / "shanshui-bench") + " --stage curvature --quick --out " +
                           test::quote(dir.path()));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("1 of 4 bench programs failed"), std::string::npos) << r.output;
  const std::string index = readText(dir / "README.md");
  EXPECT_NE(index.find("| bench_curvature_tradeoff |"), std::string::npos);
  EXPECT_NE(index.find("**failed**: error: "), std::string::npos) << index;
  EXPECT_NE(index.find("curvature_tradeoff_points.csv: is a directory"), std::string::npos)
      << "the cause, in one line: " << index;
  EXPECT_TRUE(fs::exists(dir / "ink_tradeoff_curvature_per_pixel.png")) << "the other program's plot";
}

// The stages that read real data run on the repository's own samples when nothing is beside
// it (a bare clone); the run is the one `make bench` does, but quick.
TEST(BenchCli, DataStagesNeedNothingBesideTheRepository) {
  const test::TempDir dir;
  fs::create_directories(dir / "empty");
  const auto r = test::run("SHANSHUI_DATA_DIR=" + test::quote(dir / "empty") + " " +
                           test::quote(test::binDir() / "shanshui-bench") +
                           " --stage quilt --stage param --quick --out " + test::quote(dir / "out"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(readText(dir / "out/quilt_tradeoff.csv").find("rain_strokes_scan.png"), std::string::npos);
  EXPECT_NE(readText(dir / "out/param_tradeoff.csv").find("mount_st_helens.dem"), std::string::npos);
  EXPECT_EQ(readText(dir / "out/README.md").find("failed"), std::string::npos);
}

TEST(BenchCli, RefusesAnUnknownStageAndWritesNothing) {
  const test::TempDir dir;
  const auto r = test::run(test::quote(test::binDir() / "shanshui-bench") + " --stage spline --out " +
                           test::quote(dir / "results"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("spline"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "results"));
}

}  // namespace
}  // namespace shanshui
