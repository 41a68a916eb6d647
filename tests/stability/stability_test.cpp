// The stability suite (SPEC.md section 12; CTest label `stability`): every tool on stiff
// and extreme inputs — 1×1, flat, constant, NaN, huge, tiny, degenerate, border-touching —
// and extreme parameters. Each case must end either with a clear error (non-zero exit, one
// line naming the file or parameter, no output written) or with a finite result that
// keeps the stage's invariants. Every case is a row of the summary table the suite writes
// to stability/stability.md (and .csv) in the build directory.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <mutex>
#include <sstream>

#include <nlohmann/json.hpp>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "shanshui/ink/diffusion.h"
#include "shanshui/mesh/curvature.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/noise/canvas.h"
#include "shanshui/noise/gabor.h"
#include "shanshui/noise/perlin.h"
#include "stability_table.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui {
namespace {

using test::quote;
using test::run;

// When a test process ends, its rows go to stability/<stage>.tsv in the build directory (or
// $SHANSHUI_STABILITY_DIR) and
// stability.md and .csv are rebuilt from every stage's file present (CTest runs each test
// in its own process, some at once: the summary is written to a temporary name and
// renamed, and the last process to finish leaves the whole table).
class TableWriter : public ::testing::Environment {
 public:
  void TearDown() override {
    namespace fs = std::filesystem;
    // SHANSHUI_STABILITY_DIR: where shanshui-demo wants the table for its report.
    const char* env = std::getenv("SHANSHUI_STABILITY_DIR");
    const fs::path dir = env && *env ? fs::path(env) : test::binDir().parent_path() / "stability";
    fs::create_directories(dir);
    std::map<std::string, std::vector<const Row*>> by_stage;
    for (const Row& r : table()) by_stage[r.stage].push_back(&r);
    for (const auto& [stage, rows] : by_stage) {
      std::ofstream out(dir / (stage + ".tsv"));
      for (const Row* r : rows) out << r->stage << "\t" << r->name << "\t" << r->outcome << "\n";
    }
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".tsv") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    const std::string tag = std::to_string(::getpid());
    {
      std::ofstream md(dir / ("stability.md." + tag)), csv(dir / ("stability.csv." + tag));
      // Rows first, so the summary line can count them.
      std::vector<std::array<std::string, 3>> rows;
      for (const fs::path& f : files) {
        std::ifstream in(f);
        std::string line;
        while (std::getline(in, line)) {
          const auto a = line.find('\t'), b = line.find('\t', a + 1);
          if (a == std::string::npos || b == std::string::npos) continue;
          rows.push_back({line.substr(0, a), line.substr(a + 1, b - a - 1), line.substr(b + 1)});
        }
      }
      std::map<std::string, int> kinds;
      for (const auto& r : rows) ++kinds[outcomeKind(r[2])];
      const int handled = kinds["clear error"] + kinds["finite result"];
      md << "# Stability suite\n\nEvery case ends with a clear error (non-zero exit, one line naming the file or "
            "parameter, nothing written, an existing output kept byte for byte) or a finite result that keeps the "
            "stage's invariants.\n\n"
         << "**Inputs tried: " << rows.size() << "; handled: " << handled << "; crashes: " << kinds["CRASH"]
         << "; hangs: " << kinds["HANG"] << "; partial outputs: " << kinds["PARTIAL OUTPUT"] << "; other failures: "
         << static_cast<int>(rows.size()) - handled - kinds["CRASH"] - kinds["HANG"] - kinds["PARTIAL OUTPUT"]
         << ".**\n\n| stage | case | outcome |\n|---|---|---|\n";
      csv << "stage,case,outcome\n";
      for (const auto& r : rows) {
        const std::string &stage = r[0], &name = r[1], &outcome = r[2];
        md << "| " << stage << " | " << name << " | " << outcome << " |\n";
        std::string quoted = outcome;
        for (std::size_t i = 0; (i = quoted.find('"', i)) != std::string::npos; i += 2) quoted.insert(i, "\"");
        csv << stage << "," << name << ",\"" << quoted << "\"\n";
      }
    }
    fs::rename(dir / ("stability.md." + tag), dir / "stability.md");
    fs::rename(dir / ("stability.csv." + tag), dir / "stability.csv");
  }
};
const auto* const kTableWriter = ::testing::AddGlobalTestEnvironment(new TableWriter);

std::string bin(const char* name) {
  return quote(test::binDir() / name);
}

// What a successful run must satisfy; returns a short description of the result.
using Check = std::function<std::string(const std::filesystem::path& output)>;

std::string meshIsFinite(const std::filesystem::path& p) {
  const mesh::PolygonSoup soup = mesh::readPolygonSoup(p);
  EXPECT_GT(soup.faces.size(), 0u) << p;
  for (const auto& v : soup.positions) {
    EXPECT_TRUE(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) << p;
  }
  for (const auto& f : soup.faces)
    for (std::size_t i : f) EXPECT_LT(i, soup.positions.size()) << p;
  return std::to_string(soup.positions.size()) + " vertices, " + std::to_string(soup.faces.size()) +
         " faces, all finite";
}

Check imageIsFinite(int width, int height) {
  return [=](const std::filesystem::path& p) {
    const image::Image img = image::loadImage(p);
    if (width > 0) {
      EXPECT_EQ(img.width, width) << p;
      EXPECT_EQ(img.height, height) << p;
    }
    for (float v : img.pixels) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f) << p;
    return std::to_string(img.width) + "x" + std::to_string(img.height) + ", values finite in [0, 1]";
  };
}

// Runs `args` (with "-o OUTPUT" appended) and classifies the outcome; `names` is what an
// error message must contain (the input's file name or the parameter).
void runCase(const std::string& stage, const std::string& name, const std::string& command,
             const std::filesystem::path& output, const std::string& names, const Check& check) {
  SCOPED_TRACE(stage + ": " + name);
  std::filesystem::remove(output);
  const auto r = run(command + " -o " + quote(output));
  std::string outcome;
  if (r.exit_code != 0) {
    const std::vector<std::string> errors = errorLines(r.output);
    EXPECT_EQ(errors.size(), 1u) << r.output;
    const std::string message = errors.empty() ? r.output : errors.front();
    EXPECT_NE(message.find(names), std::string::npos) << "the message should name '" << names << "': " << r.output;
    EXPECT_FALSE(std::filesystem::exists(output)) << "an error left an output behind";
    EXPECT_TRUE(r.exit_code > 0 && r.exit_code < 128) << "killed or crashed: " << r.output;
    outcome = (r.exit_code < 0 || r.exit_code >= 128) ? "CRASH: " + message
              : std::filesystem::exists(output)       ? "PARTIAL OUTPUT: " + message
                                                      : "clear error: " + message;
    // Paths of this machine stay out of the table.
    const auto slash = outcome.find('/');
    if (slash != std::string::npos) {
      const auto end = outcome.find_first_of(":' ", slash);
      const std::string path = outcome.substr(slash, end == std::string::npos ? std::string::npos : end - slash);
      outcome.replace(slash, path.size(), std::filesystem::path(path).filename().string());
    }
  } else {
    EXPECT_TRUE(std::filesystem::exists(output)) << r.output;
    outcome = std::filesystem::exists(output) ? "finite result: " + check(output) : "NO OUTPUT";
  }
  for (char& c : outcome)
    if (c == '|' || c == '\n') c = ' ';
  table().push_back({stage, name, outcome});
}

void writeText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

std::string grid(int cols, int rows, double cell, const std::string& values) {
  std::ostringstream g;
  g << "ncols " << cols << "\nnrows " << rows << "\nxllcorner 500000\nyllcorner 4000000\ncellsize " << cell
    << "\nNODATA_value -9999\n"
    << values;
  return g.str();
}

TEST(Stability, TerrainOnStiffHeightfields) {
  test::TempDir dir;
  image::saveImage(image::Image(1, 1, 1, 0.5f), dir / "one.png");
  image::saveImage(image::Image(2, 2, 1, 0.5f), dir / "two.png");
  image::saveImage(image::Image(64, 48, 1, 0.0f), dir / "flat.png", image::PixelDepth::UInt16);
  image::Image spike(33, 33, 1, 0.0f);
  spike.at(0, 0, 0) = 1.0f;  // a spike in the corner: touches the border
  image::saveImage(spike, dir / "spike.png", image::PixelDepth::UInt16);
  writeText(dir / "nan.asc", grid(3, 3, 10, "1 2 3\n4 nan 6\n7 8 9\n"));
  writeText(dir / "inf.asc", grid(3, 3, 10, "1 2 3\n4 inf 6\n7 8 9\n"));
  writeText(dir / "holes.asc", grid(4, 3, 10, "1 -9999 3 4\n-9999 -9999 -9999 -9999\n9 10 -9999 12\n"));
  writeText(dir / "huge.asc", grid(2, 2, 10, "1e300 -1e300\n1e300 0\n"));
  writeText(dir / "tiny_cells.asc", grid(3, 3, 1e-9, "1 2 3\n4 5 6\n7 8 9\n"));
  const std::string t = bin("shanshui-terrain") + " ";
  const auto out = dir / "t.obj";
  runCase("terrain", "1x1 height map", t + quote(dir / "one.png"), out, "one.png", meshIsFinite);
  runCase("terrain", "2x2 height map", t + quote(dir / "two.png"), out, "two.png", meshIsFinite);
  runCase("terrain", "flat 64x48 (16-bit zeros)", t + quote(dir / "flat.png"), out, "flat.png", meshIsFinite);
  runCase("terrain", "spike on the border", t + quote(dir / "spike.png") + " --z-scale 1000", out, "spike.png",
          meshIsFinite);
  runCase("terrain", "NaN sample", t + quote(dir / "nan.asc"), out, "nan.asc", meshIsFinite);
  runCase("terrain", "infinite sample", t + quote(dir / "inf.asc"), out, "inf.asc", meshIsFinite);
  runCase("terrain", "NODATA holes and a NODATA row", t + quote(dir / "holes.asc"), out, "holes.asc", meshIsFinite);
  runCase("terrain", "heights of ±1e300", t + quote(dir / "huge.asc"), out, "huge.asc", meshIsFinite);
  writeText(dir / "high.asc", grid(2, 2, 10, "1e14 0\n0 0\n"));
  runCase("terrain", "height of 1e14 times z-scale 100", t + quote(dir / "high.asc") + " --z-scale 100", out,
          "high.asc", meshIsFinite);
  runCase("terrain", "cells of 1e-9 m", t + quote(dir / "tiny_cells.asc"), out, "tiny_cells.asc", meshIsFinite);
  runCase("terrain", "z-scale 0", t + quote(dir / "two.png") + " --z-scale 0", out, "--z-scale", meshIsFinite);
  runCase("terrain", "z-scale NaN", t + quote(dir / "two.png") + " --z-scale nan", out, "--z-scale", meshIsFinite);
  runCase("terrain", "step far beyond the grid", t + quote(dir / "flat.png") + " --step 1000000", out, "--step",
          meshIsFinite);
  runCase("terrain", "max-vertices 1", t + quote(dir / "flat.png") + " --max-vertices 1", out, "--max-vertices",
          meshIsFinite);
}

TEST(Stability, RepairOnDegenerateMeshes) {
  test::TempDir dir;
  writeText(dir / "collinear.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 1 2\n");
  writeText(dir / "point.off", "OFF\n3 1 0\n1 1 1\n1 1 1\n1 1 1\n3 0 1 2\n");
  writeText(dir / "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 4\nf 2 3 4\n");
  writeText(dir / "one.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  writeText(dir / "huge.obj", "v -1e30 -1e30 0\nv 1e30 -1e30 0\nv 0 1e30 1e30\nf 1 2 3\n");
  writeText(dir / "tiny.obj", "v 0 0 0\nv 1e-30 0 0\nv 0 1e-30 1e-30\nf 1 2 3\n");
  writeText(dir / "twice.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3\nf 3 2 1\n");
  writeText(dir / "bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
  const std::string r = bin("shanshui-repair") + " ";
  const auto out = dir / "r.obj";
  runCase("repair", "one collinear triangle", r + quote(dir / "collinear.off"), out, "collinear.off", meshIsFinite);
  runCase("repair", "one triangle on a point", r + quote(dir / "point.off"), out, "point.off", meshIsFinite);
  runCase("repair", "a NaN vertex", r + quote(dir / "nan.obj"), out, "nan.obj", meshIsFinite);
  runCase("repair", "a single triangle", r + quote(dir / "one.obj"), out, "one.obj", meshIsFinite);
  runCase("repair", "coordinates of 1e30", r + quote(dir / "huge.obj"), out, "huge.obj", meshIsFinite);
  runCase("repair", "edges of 1e-30", r + quote(dir / "tiny.obj"), out, "tiny.obj", meshIsFinite);
  runCase("repair", "the same face three times", r + quote(dir / "twice.obj"), out, "twice.obj", meshIsFinite);
  runCase("repair", "an index past the vertices", r + quote(dir / "bad_index.obj"), out, "bad_index.obj", meshIsFinite);
}

TEST(Stability, TextureToolsOnStiffImages) {
  test::TempDir dir;
  image::saveImage(image::Image(1, 1, 1, 0.5f), dir / "one.png");
  image::Image two(2, 1, 1, 0.0f);
  two.at(1, 0, 0) = 1.0f;
  image::saveImage(two, dir / "two_levels.png");
  image::Image edge(24, 24, 1, 1.0f);
  for (int y = 0; y < 24; ++y) edge.at(0, y, 0) = 0.0f;  // ink only on the border
  image::saveImage(edge, dir / "border.png");
  image::Image near_flat(16, 16, 1, 0.5f);
  near_flat.at(3, 3, 0) = 0.5f + 1.0f / 65535;
  image::saveImage(near_flat, dir / "near_flat.tif", image::PixelDepth::UInt16);
  const std::string e = bin("shanshui-enhance") + " ";
  const auto png = dir / "e.png";
  runCase("enhance", "1x1 image", e + quote(dir / "one.png"), png, "one.png", imageIsFinite(1, 1));
  runCase("enhance", "two pixels, two levels", e + quote(dir / "two_levels.png"), png, "two_levels.png",
          imageIsFinite(2, 1));
  runCase("enhance", "ink only on the border", e + quote(dir / "border.png"), png, "border.png", imageIsFinite(24, 24));
  runCase("enhance", "one 16-bit step of contrast", e + quote(dir / "near_flat.tif"), png, "near_flat.tif",
          imageIsFinite(16, 16));
  runCase("enhance", "percentiles 0:100", e + quote(dir / "border.png") + " --auto 0:100", png, "--auto",
          imageIsFinite(24, 24));
  runCase("enhance", "range NaN", e + quote(dir / "border.png") + " --range nan:1", png, "--range",
          imageIsFinite(24, 24));

  const std::string q = bin("shanshui-quilt") + " ";
  runCase("quilt", "1x1 sample", q + quote(dir / "one.png") + " --size 8x8", png, "one.png", imageIsFinite(8, 8));
  runCase("quilt", "sample exactly one block", q + quote(dir / "border.png") + " --size 64x40 --block 24", png,
          "border.png", imageIsFinite(64, 40));
  runCase("quilt", "output of one block, tileable",
          q + quote(dir / "border.png") + " --size 24x24 --block 24 --tileable", png, "border.png",
          imageIsFinite(24, 24));
  runCase("quilt", "block 3, overlap 1", q + quote(dir / "border.png") + " --size 30x30 --block 3 --overlap 1", png,
          "border.png", imageIsFinite(30, 30));
  runCase("quilt", "tolerance 1e9", q + quote(dir / "border.png") + " --size 48x48 --block 12 --tolerance 1e9", png,
          "border.png", imageIsFinite(48, 48));
  runCase("quilt", "size 0x0", q + quote(dir / "border.png") + " --size 0x0", png, "--size", imageIsFinite(0, 0));
  runCase("quilt", "size 100000x100000", q + quote(dir / "border.png") + " --size 100000x100000 --block 12", png,
          "--size: 100000x100000", imageIsFinite(0, 0));
}

TEST(Stability, ParameterizationOnStiffMeshes) {
  test::TempDir dir;
  writeText(dir / "one.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  writeText(dir / "needle.obj", "v 0 0 0\nv 1 0 0\nv 0.5 1e-9 0\nv 0.5 1 0\nf 1 2 3\nf 1 3 4\nf 3 2 4\n");
  writeText(dir / "tetra.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
  writeText(dir / "vertical.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0 1\nf 1 2 4\nf 1 4 3\n");
  const std::string p = bin("shanshui-param") + " ";
  const auto out = dir / "p.obj";
  for (const char* method : {"auto", "xy", "lscm", "arap", "charts"}) {
    const std::string m = std::string(" --method ") + method;
    runCase("param", std::string("single triangle, ") + method, p + quote(dir / "one.obj") + m, out, "one.obj",
            meshIsFinite);
    runCase("param", std::string("needle triangle, ") + method, p + quote(dir / "needle.obj") + m, out, "needle.obj",
            meshIsFinite);
    runCase("param", std::string("closed tetrahedron, ") + method, p + quote(dir / "tetra.obj") + m, out, "tetra.obj",
            meshIsFinite);
    runCase("param", std::string("vertical wall, ") + method, p + quote(dir / "vertical.obj") + m, out, "vertical.obj",
            meshIsFinite);
  }
}

TEST(Stability, RendererOnStiffScenesAndParameters) {
  test::TempDir dir;
  writeText(dir / "one.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  writeText(dir / "sliver.obj", "v 0 0 0\nv 1000 0 0\nv 500 1e-6 0\nv 500 500 1\nf 1 2 3\nf 1 3 4\n");
  image::saveImage(image::Image(16, 16, 1, 0.0f), dir / "flat.png");
  const std::string r = bin("shanshui-render") + " ";
  const std::string dem = test::sourceDir().string() + "/samples/terrain/mount_st_helens.dem";
  const std::string small = " --size 64x48 --set objects.0.max_vertices=3000";
  const auto out = dir / "r.png";
  runCase("render", "a single triangle", r + quote(dir / "one.obj") + " --size 64x48", out, "one.obj",
          imageIsFinite(64, 48));
  runCase("render", "a sliver of 1e-6 by 1000", r + quote(dir / "sliver.obj") + " --size 64x48", out, "sliver.obj",
          imageIsFinite(64, 48));
  runCase("render", "a flat DEM", r + quote(dir / "flat.png") + " --size 64x48", out, "flat.png",
          imageIsFinite(64, 48));
  runCase("render", "1x1 picture", r + quote(dem) + " --size 1x1 --set objects.0.max_vertices=3000", out, "",
          imageIsFinite(1, 1));
  struct Set {
    const char* name;
    const char* sets;
  };
  const Set sets[] = {
      {"curve factor 100 (the maximum), threshold 1",
       "objects.0.lines.curve_factor=100 --set objects.0.lines.threshold=1"},
      {"Gaussian steps of sigma 0", "objects.0.shading.sigma=0"},
      {"all tones 0", "objects.0.shading.tones=[0,0,0,0,0]"},
      {"z-scale 1e-3", "objects.0.z_scale=0.001"},
      {"zoom 1000 (camera inside the mountain)", "camera.zoom=1000"},
      {"zoom 0.001", "camera.zoom=0.001"},
      {"light straight up", "light.direction=[0,0,1]"},
      {"canvas silk, N' 1024, grain 0.5", "canvas.type=silk --set canvas.impulses=1024 --set canvas.grain=0.5"},
      {"canvas rice paper, N' 1, grain 256", "canvas.type=rice_paper --set canvas.impulses=1 --set canvas.grain=256"},
      {"canvas contrast 1", "canvas.contrast=1"},
      {"diffusion d 256, n 100, f 1",
       "diffusion.ring_steps=256 --set diffusion.iterations=100 --set diffusion.attenuation=1"},
      {"diffusion absorb 1000, residual 0",
       "diffusion.iterations=10 --set diffusion.absorb=1000 --set diffusion.residual=0"},
      {"diffusion with the canvas's absorbency at 0", "diffusion.iterations=5 --set canvas.absorbency=0"},
      {"pigment 16 layers thick, following the ink, texture 1",
       "objects.0.pigment.name='\"ochre\"' --set objects.0.pigment.thickness=16 --set objects.0.pigment.follow_ink=1 "
       "--set objects.0.pigment.texture=1"},
      {"custom pigment at the limits (on white 0.999, on black 1e-6)",
       "objects.0.pigment.name='\"custom\"' --set objects.0.pigment.on_white=[0.999,0.999,0.999] --set "
       "objects.0.pigment.on_black=[1e-6,1e-6,0.998]"},
      {"shadow map 8192, softness 16, bias 0",
       "shadow.pigment.name='\"ink\"' --set shadow.resolution=8192 --set shadow.softness=16 --set shadow.bias=0"},
      {"shadow map 64, light straight up",
       "shadow.pigment.name='\"indigo\"' --set shadow.resolution=64 --set "
       "light.direction=[0,0,1]"},
      {"edges 15 x 15 taps, radius 64, wobble 32",
       "edges.enabled=true --set edges.samples=15 --set edges.radius=64 --set edges.wobble=32 --set edges.strength=8"},
      {"substrate at every maximum",
       "substrate.enabled=true --set substrate.roughness=4 --set "
       "substrate.granulation=16 --set substrate.dry_brush=1 --set substrate.lighting=1 "
       "--set substrate.distortion=32 --set substrate.dry_edge=0.001"},
      {"substrate without a canvas (value noise)", "substrate.enabled=true --set canvas.type=none"},
      {"motion blur: the land spinning 36000 degrees/s, trail 64, interval 10 s, no paint, no water",
       "motion_blur.enabled=true --set objects.0.spin=36000 --set motion_blur.length=64 --set "
       "motion_blur.interval=10 --set motion_blur.paint=0 --set motion_blur.water=0"},
      {"motion blur: the land flying off at 1e9 units/s",
       "motion_blur.enabled=true --set objects.0.velocity=[1e9,0,0] --set motion_blur.interval=1e-4"},
      {"trees of 1e-6 m, one grove of 1000, slope limit 0",
       "objects.0.trees.enabled=true --set objects.0.trees.size=1e-6 --set objects.0.trees.grove=1000 --set "
       "objects.0.trees.max_slope=0"},
      {"trees 1e6 m high, spread 2, every kind",
       "objects.0.trees.enabled=true --set objects.0.trees.size=1e6 --set "
       "objects.0.trees.size_spread=2 --set objects.0.trees.kinds=[1000,1000,1000,1000]"},
      {"groves and dot clusters a million metres wide",
       "objects.0.trees.enabled=true --set objects.0.trees.grove_radius=1e6 "
       "--set objects.0.trees.grove=1 --set objects.0.dots.enabled=true --set "
       "objects.0.dots.spread=1e6"},
      {"trees in a band of zero width at the top, no kind",
       "objects.0.trees.enabled=true --set "
       "objects.0.trees.band=[0.999999,1] --set objects.0.trees.kinds=[0,0,0,0]"},
      {"moss dots 64 px, clusters of 30, dots at every tree",
       "objects.0.dots.enabled=true --set objects.0.dots.size=64 --set "
       "objects.0.dots.cluster=30 --set objects.0.trees.enabled=true --set "
       "objects.0.dots.at_trees=1"},
  };
  for (const Set& s : sets) {
    runCase("render", s.name, r + quote(dem) + small + " --set " + s.sets, out, "", imageIsFinite(64, 48));
  }
  runCase("render", "curve factor -1", r + quote(dem) + small + " --set objects.0.lines.curve_factor=-1", out,
          "curve_factor", imageIsFinite(64, 48));
  runCase("render", "custom pigment darker on white than on black",
          r + quote(dem) + small +
              " --set objects.0.pigment.name='\"custom\"' --set objects.0.pigment.on_black=[0.9,0.1,0.1]",
          out, "objects.0.pigment.on_black", imageIsFinite(64, 48));
  runCase("render", "canvas impulses NaN", r + quote(dem) + small + " --set canvas.impulses=nan", out,
          "canvas.impulses", imageIsFinite(64, 48));
  runCase("render", "trees at 10000 per hectare",
          r + quote(dem) + small + " --set objects.0.trees.enabled=true --set objects.0.trees.density=10000", out,
          "objects.0.trees.density", imageIsFinite(64, 48));
}

// Library stages: `stage` runs the case and returns a description of its finite result
// (checking invariants with EXPECT) or throws Error, which is recorded as a clear error.
void libraryCase(const std::string& stage, const std::string& name, const std::function<std::string()>& body) {
  SCOPED_TRACE(stage + ": " + name);
  std::string outcome;
  try {
    outcome = "finite result: " + body();
  } catch (const Error& e) {
    outcome = std::string("clear error: ") + e.what();
  }
  table().push_back({stage, name, outcome});
}

bool allFinite(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); });
}

TEST(Stability, CurvatureOnStiffMeshes) {
  // Invariants: finite curvature at every vertex; a finite feature size, 0 meaning flat.
  auto both = [](const mesh::Mesh& m) {
    std::string sizes;
    for (const mesh::VertexCurvature& c : {mesh::estimateCurvature(m), mesh::estimateCurvatureByFit(m)}) {
      EXPECT_EQ(c.magnitude.size(), m.positions.size());
      EXPECT_TRUE(allFinite(c.magnitude) && allFinite(c.mean) && allFinite(c.gaussian));
      const double size = mesh::curvatureFeatureSize(m, c);
      EXPECT_TRUE(std::isfinite(size) && size >= 0) << size;
      char text[64];
      std::snprintf(text, sizeof text, "%s%.3g", sizes.empty() ? "" : " / ", size);
      sizes += text;
    }
    return std::to_string(m.positions.size()) +
           " vertices, both estimators finite; feature size (cotangent / quadric, 0 = flat) " + sizes;
  };
  mesh::Mesh one;
  one.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  one.triangles = {{0, 1, 2}};
  mesh::Mesh collinear = one;
  collinear.positions[2] = {2, 0, 0};
  const auto flat = test::heightGrid(20, 20, 1.0, [](double, double) { return 0.0; });
  const auto needles = test::heightGrid(40, 3, 1.0, [](double x, double y) { return 1e-7 * x * y; });
  const auto cliff = test::heightGrid(20, 20, 1.0, [](double x, double) { return x < 10 ? 0.0 : 1e6; });
  auto scaled = [](mesh::Mesh m, double s) {
    for (auto& p : m.positions) p *= s;
    return m;
  };
  const auto sphere = test::uvSphere(1.0, 12, 24);
  libraryCase("curvature", "a single triangle", [&] { return both(one); });
  libraryCase("curvature", "a collinear (zero-area) triangle", [&] { return both(collinear); });
  libraryCase("curvature", "a flat grid (k = 0 everywhere)", [&] { return both(flat); });
  libraryCase("curvature", "a 1e-7 twist on a thin strip", [&] { return both(needles); });
  libraryCase("curvature", "a 1e6 cliff", [&] { return both(cliff); });
  libraryCase("curvature", "a sphere scaled by 1e-12", [&] { return both(scaled(sphere, 1e-12)); });
  libraryCase("curvature", "a sphere scaled by 1e12", [&] { return both(scaled(sphere, 1e12)); });
}

TEST(Stability, InkDiffusionOnStiffPictures) {
  // Conservation and no negative ink, on pictures and options at the edges of their ranges.
  auto field = [](int w, int h, double value, bool border_only) {
    ink::InkField f{w, h, std::vector<double>(static_cast<std::size_t>(w) * h, border_only ? 0.0 : value)};
    if (border_only)
      for (int x = 0; x < w; ++x) f.ink[static_cast<std::size_t>(x)] = value;
    return f;
  };
  auto diffuse = [](const ink::InkField& in, const ink::DiffusionOptions& o) {
    const std::vector<float> absorbency(in.ink.size(), 1.0f);
    const ink::InkField out = ink::diffuseInk(in, absorbency, o);
    double lowest = 0;
    for (double v : out.ink) {
      EXPECT_TRUE(std::isfinite(v));
      lowest = std::min(lowest, v);
    }
    EXPECT_GE(lowest, 0.0);
    // The main region adds ink by design; the boundary iterations only move it.
    ink::DiffusionOptions main_only = o;
    main_only.iterations = 0;
    const double before = ink::diffuseInk(in, absorbency, main_only).total();
    EXPECT_NEAR(out.total(), before, 1e-9 * std::max(1.0, before));
    char text[160];
    std::snprintf(text, sizeof text, "no negative ink, boundary ink conserved (%.3g of %.3g)", out.total(), before);
    return std::string(text);
  };
  ink::DiffusionOptions extreme;
  extreme.ring_steps = 64;
  extreme.iterations = 100;
  extreme.attenuation = 1.0;
  extreme.absorb = 1000.0;
  extreme.residual = 0.0;
  libraryCase("diffusion", "1x1 stroke, extreme options", [&] { return diffuse(field(1, 1, 1.0, false), extreme); });
  libraryCase("diffusion", "empty 32x32", [&] { return diffuse(field(32, 32, 0.0, false), extreme); });
  libraryCase("diffusion", "all ink 32x32", [&] { return diffuse(field(32, 32, 1.0, false), extreme); });
  libraryCase("diffusion", "a stroke along the border", [&] { return diffuse(field(32, 32, 1.0, true), extreme); });
  ink::DiffusionOptions bad = extreme;
  bad.attenuation = std::nan("");
  libraryCase("diffusion", "attenuation NaN", [&] { return diffuse(field(8, 8, 1.0, true), bad); });
  bad = extreme;
  bad.iterations = -1;
  libraryCase("diffusion", "iterations -1", [&] { return diffuse(field(8, 8, 1.0, true), bad); });
}

TEST(Stability, NoiseOnExtremeParameters) {
  auto gabor = [](double a, double F0, double impulses) {
    noise::GaborOptions o;
    o.a = a;
    o.F0 = F0;
    o.impulses = impulses;
    const noise::GaborNoise g(o);
    double worst = 0;
    for (int i = 0; i < 64; ++i) {
      const double v = g(i * 7.3 / a, i * 3.1 / a);
      EXPECT_TRUE(std::isfinite(v));
      worst = std::max(worst, std::abs(v));
    }
    EXPECT_TRUE(std::isfinite(g.variance()) && g.variance() > 0);
    return "64 samples finite, largest " + std::to_string(worst);
  };
  libraryCase("noise", "Gabor N' 1", [&] { return gabor(0.05, 0.06, 1); });
  libraryCase("noise", "Gabor N' 1024", [&] { return gabor(0.05, 0.06, 1024); });
  libraryCase("noise", "Gabor a 1e-3 (kernels of 1000 units)", [&] { return gabor(1e-3, 0.0, 16); });
  libraryCase("noise", "Gabor a 1e3", [&] { return gabor(1e3, 0.0, 16); });
  libraryCase("noise", "Gabor F0 0", [&] { return gabor(0.05, 0.0, 64); });
  libraryCase("noise", "Gabor N' 0", [&] { return gabor(0.05, 0.06, 0); });
  libraryCase("noise", "Perlin at 1e9", [&] {
    const double v = noise::perlin(1e9 + 0.5, -1e9 + 0.25, 3.5);
    EXPECT_TRUE(std::isfinite(v) && std::abs(v) <= 1.0);
    return "value " + std::to_string(v);
  });
  libraryCase("noise", "canvas sigma at grain 0.5 and 256, N' 1 and 1024", [&] {
    for (double r : {0.5, 256.0})
      for (double n : {1.0, 1024.0})
        for (bool silk : {false, true}) {
          noise::CanvasNoiseOptions o;
          o.silk = silk;
          o.radius = r;
          o.impulses = n;
          const double s = noise::canvasSigma(o);
          EXPECT_TRUE(std::isfinite(s) && s > 0) << r << " " << n;
        }
    return std::string("sigma finite and positive for all eight");
  });
}

// Batches (--manifest): a manifest that is odd in itself. Each ends with one clear error
// naming the manifest, or with every item run and the failed ones listed by line.
TEST(Stability, BatchManifestsOnStiffInput) {
  test::TempDir dir;
  image::saveImage(image::Image(8, 8, 1, 0.25f), dir / "flat.png");
  image::Image ramp(8, 8, 1, 0.0f);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) ramp.at(x, y, 0) = static_cast<float>(x) / 7.0f;
  image::saveImage(ramp, dir / "ramp.png");
  const std::string e = "cd " + quote(dir.path()) + " && " + bin("shanshui-enhance") + " --manifest ";
  auto record = [&](const std::string& name, const std::string& manifest, const std::string& text, int want_exit,
                    const std::string& want) {
    SCOPED_TRACE("batch: " + name);
    if (!text.empty() || !std::filesystem::exists(dir / manifest)) writeText(dir / manifest, text);
    const auto r = run(e + quote(manifest));
    EXPECT_EQ(r.exit_code, want_exit) << r.output;
    EXPECT_NE(r.output.find(want), std::string::npos) << r.output;
    std::string last;
    std::istringstream in(r.output);
    for (std::string line; std::getline(in, line);)
      if (line.find(want) != std::string::npos) last = line;
    for (char& c : last)
      if (c == '|') c = ' ';
    table().push_back(
        {"batch", name, (r.exit_code == 0 ? "finished: " : "exit " + std::to_string(r.exit_code) + ": ") + last});
  };
  record("no items (comments only)", "empty.txt", "# nothing\n\n   \n", 1, "empty.txt: the manifest has no items");
  std::filesystem::create_directories(dir / "a_dir.txt");
  record("the manifest is a directory", "a_dir.txt", "", 1, "a_dir.txt: is a directory, expected a --manifest");
  record("binary junk (NUL bytes)", "junk.txt", std::string("ramp.png -o j.png\n\0\x01\xff\n", 21), 1,
         "batch of 2: 1 done, 1 failed");
  record("CRLF line endings", "crlf.txt", "ramp.png -o c1.png\r\nramp.png -o c2.png\r\n", 0,
         "batch of 2: 2 done, 0 failed");
  record("a 100 000-character argument", "long.txt",
         "ramp.png -o " + std::string(100000, 'x') + ".png\nramp.png -o l.png\n", 1, "batch of 2: 1 done, 1 failed");
  std::string many;
  for (int i = 0; i < 40; ++i)
    many += (i % 2 ? "flat.png" : "ramp.png") + std::string(" -o m") + std::to_string(i) + ".png\n";
  record("40 items, every other one a flat image (refused)", "many.txt", many, 1, "batch of 40: 20 done, 20 failed");
  // The manifest is read whole before any item runs: item 1 replacing it with a picture
  // does not change what item 2 is.
  record("item 1 writes its picture over the manifest", "self.png", "ramp.png -o self.png\nramp.png -o self2.png\n", 0,
         "batch of 2: 2 done, 0 failed");
  EXPECT_EQ(image::loadImage(dir / "self.png").width, 8);
  EXPECT_TRUE(std::filesystem::exists(dir / "self2.png"));
  for (int i = 0; i < 40; i += 2) EXPECT_TRUE(std::filesystem::exists(dir / ("m" + std::to_string(i) + ".png"))) << i;
  EXPECT_FALSE(std::filesystem::exists(dir / "m1.png")) << "a refused item wrote an output";
}

}  // namespace
}  // namespace shanshui
