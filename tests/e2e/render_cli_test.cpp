// End-to-end: shanshui-render on scene files, its statistics, and scene-file errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "shanshui/image/image_io.h"
#include "test_support.h"

namespace shanshui {
namespace {

using nlohmann::json;
using test::quote;
using test::run;

std::string bin(const char* name) {
  return quote(test::binDir() / name);
}
std::string sampleScene() {
  return quote(test::sourceDir() / "samples/scenes/default.json");
}

json readJson(const std::filesystem::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

std::set<std::string> passNames(const json& frame) {
  std::set<std::string> names;
  for (const auto& [k, v] : frame["passes"].items()) names.insert(k);
  return names;
}

// --benchmark on llvmpipe: frames back to back, per-pass GPU medians (the elements pass
// among them: the sample grows trees), no picture written.
TEST(RenderCli, BenchmarkTimesEveryPassOverFramesBackToBack) {
  test::TempDir dir;
  const auto r = run(bin("shanshui-render") + " " + sampleScene() + " --benchmark 3 --size 96x64 --stats " +
                     quote(dir / "b.json") + " --set objects.0.max_vertices=5000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("elements"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("fps"), std::string::npos) << r.output;
  const json b = readJson(dir / "b.json");
  EXPECT_EQ(b["frames"], 3);
  EXPECT_EQ(b["size"], json({96, 64}));
  for (const char* pass : {"gbuffer", "canvas", "elements", "ink"}) {
    ASSERT_TRUE(b["pass_gpu_ms"].contains(pass)) << pass;
    EXPECT_GT(b["pass_gpu_ms"][pass]["median"].get<double>(), 0.0) << pass;
    EXPECT_GE(b["pass_gpu_ms"][pass]["p90"].get<double>(), b["pass_gpu_ms"][pass]["median"].get<double>()) << pass;
  }
  EXPECT_GE(b["frame_wall_ms"]["median"].get<double>(), b["passes_gpu_ms"]["median"].get<double>() * 0.5);
  // Frames in flight, their times read late: every counted frame's passes came back.
  EXPECT_EQ(b["frames_in_flight"], 2);
  EXPECT_GT(b["fps"].get<double>(), 0.0);
  EXPECT_GT(b["submit_cpu_ms"]["median"].get<double>(), 0.0);
  EXPECT_GT(b["frame_cpu_ms"].get<double>(), 0.0);
  EXPECT_LE(b["submit_cpu_ms"]["median"].get<double>(), b["frame_wall_ms"]["p90"].get<double>() * 1.5);
  EXPECT_GT(b["elements"][0]["count"].get<int>(), 0);
  EXPECT_LT(b["elements"][0]["place_seconds"].get<double>(), 5.0);
  EXPECT_FALSE(std::filesystem::exists(dir / "b.png"));
  const auto bad = run(bin("shanshui-render") + " " + sampleScene() + " --benchmark -2");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--benchmark"), std::string::npos) << bad.output;
}

TEST(RenderCli, StatsListThePassesBuiltAndTheirGpuTimePerFrame) {
  test::TempDir dir;
  const auto r =
      run(bin("shanshui-render") + " " + sampleScene() + " -o " + quote(dir / "f.png") +
          " --size 160x120 --frames 3 --stats " + quote(dir / "s.json") + " --set objects.0.max_vertices=20000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"f_0000.png", "f_0001.png", "f_0002.png"}) {
    const image::Image img = image::loadImage(dir / f);
    EXPECT_EQ(img.width, 160);
    EXPECT_EQ(img.height, 120);
  }
  const json s = readJson(dir / "s.json");
  EXPECT_EQ(s["passes_built"], json({"gbuffer", "canvas", "elements", "ink"}));
  // The sample draws its lines as strokes: the ink pass has a lines stage before it, which
  // also samples the shading's noise (SHADING). Its slope wrinkles on planar UVs are
  // computed in the ink pass, not the G-buffer's. Its dissolved border's bare land is drawn
  // apart (llvmpipe's fragment passes).
  EXPECT_EQ(s["variants"]["ink"],
            json({"LINES STROKES SHADING WRINKLE WRINKLE_SLOPE CANVAS ELEMENTS SINGLE_OBJECT BORDER MIST",
                  "lines: SINGLE_OBJECT BORDER MIST SHADING", "bare land: BARE"}));
  // The tiles canvas: its tile, the surfaces' and the background's programs (rice paper's
  // fibres, spots and mottle; the grain pinned to the surface under zoom), the mottle's.
  EXPECT_EQ(s["variants"]["canvas"],
            json({"CANVAS_TILE", "SPACES=2 SINGLE_OBJECT PAPER_MARKS MOTTLE GRAIN_ON_SURFACE",
                  "SPACES=2 BACKGROUND PAPER_MARKS MOTTLE GRAIN_ON_SURFACE", "SPACES=1 MOTTLE"}));
  // No wash: the G-buffer leaves the erosion noise (SURFACE) to the ink pass.
  EXPECT_EQ(s["variants"]["gbuffer"], json({"OBJECT_CURVATURE"}));
  ASSERT_EQ(s["frames"].size(), 3u);
  for (const json& f : s["frames"]) {
    EXPECT_FALSE(f["cached"].get<bool>());
    EXPECT_EQ(passNames(f), std::set<std::string>({"gbuffer", "canvas", "elements", "lines", "ink"}));
    double sum = 0;
    for (const auto& [k, v] : f["passes"].items()) {
      EXPECT_GE(v.get<double>(), 0.0) << k;
      sum += v.get<double>();
    }
    // GPU times are real: they fit inside the frame's wall time (which waits for them).
    EXPECT_LE(sum, f["frame_ms"].get<double>() * 1.05 + 1.0);
  }
  // Frames along the camera path differ.
  EXPECT_NE(image::loadImage(dir / "f_0000.png").pixels, image::loadImage(dir / "f_0002.png").pixels);
}

// A frame that makes more tree and dot marks than it has room for says so, once, on stderr
// and in the statistics (the room lowered with SHANSHUI_ELEMENT_MARKS, as the renderer's
// test does); the default room holds the sample's, and then nothing is said.
TEST(RenderCli, MarksWithoutRoomAreReportedNotLostSilently) {
  test::TempDir dir;
  const std::string common = sampleScene() + " --size 160x120 --frames 2 --set objects.0.max_vertices=20000";
  auto r = run("SHANSHUI_ELEMENT_MARKS=10 " + bin("shanshui-render") + " " + common + " -o " + quote(dir / "f.png") +
               " --stats " + quote(dir / "s.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string warning = "tree and dot marks had no room in the frame";
  const std::size_t first = r.output.find(warning);
  EXPECT_NE(first, std::string::npos) << r.output;
  EXPECT_EQ(r.output.find(warning, first + 1), std::string::npos) << "said once: " << r.output;
  const json s = readJson(dir / "s.json");
  for (const json& f : s["frames"]) EXPECT_GT(f.value("marks_dropped", 0), 0) << f.dump();
  r = run(bin("shanshui-render") + " " + common + " -o " + quote(dir / "g.png") + " --stats " + quote(dir / "t.json"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find(warning), std::string::npos) << r.output;
  for (const json& f : readJson(dir / "t.json")["frames"]) EXPECT_FALSE(f.contains("marks_dropped")) << f.dump();
}

// A lone coastal DEM (a quarter of it under the sea, relief 1:50, 60 samples across) is
// painted raised, with its sea as water and its grid made finer, and the tool says so, each
// in a line naming the key that undoes it.
TEST(RenderCli, ALoneCoastalDemSaysItIsRaisedAndGetsItsSea) {
  test::TempDir dir;
  {
    std::ofstream out(dir / "coast.asc");
    out << "ncols 60\nnrows 40\nxllcorner 0\nyllcorner 0\ncellsize 1000\nNODATA_value -9999\n";
    for (int r = 0; r < 40; ++r)
      for (int c = 0; c < 60; ++c)
        out << -300.0 + 1200.0 * c / 59.0 + 50.0 * std::sin(0.5 * r) << (c < 59 ? " " : "\n");
  }
  const std::string base = bin("shanshui-render") + " " + quote(dir / "coast.asc") + " --size 160x120";
  auto r = run(base + " -o " + quote(dir / "a.png"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("raised"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(objects.0.z_scale)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("is sea (water.level"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("60 x 40 samples: made 7 times finer by bicubic interpolation (objects.0.upsample)"),
            std::string::npos)
      << r.output;
  r = run(base + " -o " + quote(dir / "b.png") +
          " --set water.enabled=false --set objects.0.z_scale=1 --set objects.0.upsample=1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("note:"), std::string::npos) << "what the user set is not announced: " << r.output;
}

// The light-colour sample builds and runs the paper-and-pigment passes (the default sample,
// above, builds none of them), each with the variant its inputs need.
TEST(RenderCli, TheLightColourSampleRunsThePigmentShadowEdgesAndSubstratePasses) {
  test::TempDir dir;
  const auto r = run(bin("shanshui-render") + " " + quote(test::sourceDir() / "samples/scenes/light_colour.json") +
                     " -o " + quote(dir / "f.png") + " --size 160x120 --stats " + quote(dir / "s.json") +
                     " --set objects.0.max_vertices=5000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = readJson(dir / "s.json");
  EXPECT_EQ(s["passes_built"],
            json({"gbuffer", "canvas", "elements", "ink", "pigment", "shadow", "edges", "substrate"}));
  EXPECT_NE(s["variants"]["ink"][0].get<std::string>().find("PIGMENT"), std::string::npos);
  EXPECT_EQ(s["variants"]["edges"], json({"SHADOW"}));
  EXPECT_EQ(s["variants"]["substrate"], json({"CANVAS"}));
  ASSERT_EQ(s["frames"].size(), 1u);
  EXPECT_EQ(passNames(s["frames"][0]), std::set<std::string>({"gbuffer", "canvas", "elements", "lines", "ink",
                                                              "pigment", "shadow", "edges", "substrate"}));
}

TEST(RenderCli, ASceneWithoutWrinklesCanvasOrDiffusionRunsNoneOfThem) {
  test::TempDir dir;
  const auto r =
      run(bin("shanshui-render") + " " + sampleScene() + " -o " + quote(dir / "f.png") +
          " --size 96x64 --frames 2 --orbit 0 --set camera.path='[]' --stats " + quote(dir / "s.json") +
          " --set objects.0.max_vertices=5000 --set objects.0.wrinkle.texture='\"\"' --set canvas.type=none");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = readJson(dir / "s.json");
  for (const json& j : s["passes_built"]) {
    const std::string pass = j.get<std::string>();
    EXPECT_EQ(pass.find("wrinkle"), std::string::npos);
    EXPECT_EQ(pass.find("canvas"), std::string::npos);
    EXPECT_EQ(pass.find("diffusion"), std::string::npos);
  }
  // No shader variant samples a wrinkle texture or reads UVs.
  for (const auto& [pass, variants] : s["variants"].items()) {
    for (const json& v : variants) EXPECT_EQ(v.get<std::string>().find("WRINKLE"), std::string::npos) << pass;
  }
  // The second frame is the same view: presented from the cache, no pass ran.
  ASSERT_EQ(s["frames"].size(), 2u);
  EXPECT_FALSE(s["frames"][0]["cached"].get<bool>());
  EXPECT_TRUE(s["frames"][1]["cached"].get<bool>());
  EXPECT_TRUE(s["frames"][1]["passes"].empty());
  EXPECT_EQ(image::loadImage(dir / "f_0000.png").pixels, image::loadImage(dir / "f_0001.png").pixels);
}

TEST(RenderCli, LinesOnlyAndShadingOnlyBuildOnlyTheirShaderCode) {
  test::TempDir dir;
  const std::string base =
      bin("shanshui-render") + " " + sampleScene() + " --size 64x48 --set objects.0.max_vertices=3000";
  auto r = run(base + " -o " + quote(dir / "a.png") + " --stats " + quote(dir / "a.json") +
               " --set objects.0.shading.enabled=false");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json a = readJson(dir / "a.json");
  // Strokes only: the bands' code (BAND_LINES) is left out of the ink pass.
  EXPECT_EQ(a["variants"]["ink"], json({"LINES STROKES CANVAS ELEMENTS SINGLE_OBJECT BORDER MIST",
                                        "lines: SINGLE_OBJECT BORDER MIST", "bare land: BARE"}));
  EXPECT_EQ(a["variants"]["gbuffer"], json({"OBJECT_CURVATURE"})) << "no noise, no wrinkle texture, no UVs";
  r = run(base + " -o " + quote(dir / "b.png") + " --stats " + quote(dir / "b.json") +
          " --set objects.0.lines.enabled=false");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json b = readJson(dir / "b.json");
  EXPECT_EQ(b["variants"]["ink"], json({"SHADING WRINKLE WRINKLE_SLOPE CANVAS ELEMENTS SINGLE_OBJECT BORDER MIST"}));
  // No curvature of either kind, no UV varying, no noise (the ink pass samples it).
  EXPECT_EQ(b["variants"]["gbuffer"], json({""}));
  // Eq. 1's bands instead of strokes: no lines stage, no stroke code, the bands' code (and
  // no bare land drawn apart: the lines stage finds it).
  r = run(base + " -o " + quote(dir / "c.png") + " --stats " + quote(dir / "c.json") +
          " --set objects.0.lines.width=0");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json c = readJson(dir / "c.json");
  EXPECT_EQ(c["variants"]["ink"],
            json({"LINES BAND_LINES SHADING WRINKLE WRINKLE_SLOPE CANVAS ELEMENTS SINGLE_OBJECT BORDER MIST"}));
  EXPECT_EQ(passNames(c["frames"][0]).count("lines"), 0u);
}

TEST(RenderCli, SetChangesTheRenderedPicture) {
  test::TempDir dir;
  const std::string base =
      bin("shanshui-render") + " " + sampleScene() + " --size 128x96 --set objects.0.max_vertices=5000";
  ASSERT_EQ(run(base + " -o " + quote(dir / "a.png")).exit_code, 0);
  ASSERT_EQ(run(base + " -o " + quote(dir / "b.png") + " --set objects.0.lines.curve_factor=3").exit_code, 0);
  const image::Image a = image::loadImage(dir / "a.png"), b = image::loadImage(dir / "b.png");
  double ink_a = 0, ink_b = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) ink_a += 1 - a.pixels[i], ink_b += 1 - b.pixels[i];
  EXPECT_GT(ink_b, ink_a * 1.02) << "a larger curve factor draws more line ink";
}

// The darkest pixel's grey and the share of pixels darker than half of white.
std::pair<float, double> darkness(const image::Image& img) {
  float darkest = 1.0f;
  std::size_t dark = 0;
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      const float g = (img.at(x, y, 0) + img.at(x, y, 1) + img.at(x, y, 2)) / 3.0f;
      darkest = std::min(darkest, g);
      dark += g < 0.5f;
    }
  }
  return {darkest, static_cast<double>(dark) / (static_cast<double>(img.width) * img.height)};
}

TEST(RenderCli, EverySampleSceneAndALoneDemRenderInTheirFormat) {
  test::TempDir dir;
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::sourceDir() / "samples/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++scenes;
    SCOPED_TRACE(entry.path().filename().string());
    const json scene = readJson(entry.path());
    const bool scroll = scene.contains("output") && scene["output"].value("format", "free") == "vertical_scroll";
    const auto out = dir / (entry.path().stem().string() + ".png");
    const auto r = run(bin("shanshui-render") + " " + quote(entry.path()) + " -o " + quote(out) +
                       " --size 160x120 --set objects.0.max_vertices=20000");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const image::Image img = image::loadImage(out);
    EXPECT_EQ(img.height, 120);
    EXPECT_EQ(img.width, scroll ? 48 : 160) << "a hanging scroll is 0.4 as wide as it is tall";
    const auto [darkest, dark_share] = darkness(img);
    EXPECT_LT(darkest, 0.35f) << "some ink";
    EXPECT_LT(dark_share, 0.25) << "mostly paper";
  }
  EXPECT_GE(scenes, 4) << "the default and the three distances";
  // A DEM alone gets the sample's style: strokes, rice paper, mist, a dissolving border, wet
  // strokes, and, being 14 km across, trees and moss dots (the elements pass).
  const auto r = run(bin("shanshui-render") + " " + quote(test::sourceDir() / "samples/terrain/mount_st_helens.dem") +
                     " -o " + quote(dir / "lone.png") + " --size 160x120 --stats " + quote(dir / "lone.json") +
                     " --set objects.0.max_vertices=20000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const json s = readJson(dir / "lone.json");
  EXPECT_EQ(s["passes_built"], json({"gbuffer", "canvas", "elements", "ink"}));
  EXPECT_EQ(s["variants"]["ink"][0], "LINES STROKES SHADING CANVAS ELEMENTS MARKS WASH SINGLE_OBJECT BORDER MIST");
  EXPECT_NE(r.output.find("trees and moss dots grown"), std::string::npos) << r.output;
  EXPECT_LT(darkness(image::loadImage(dir / "lone.png")).first, 0.35f);
}

int lineCount(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

TEST(RenderCli, EveryKindOfSceneErrorHasItsOwnMessageAndWritesNothing) {
  test::TempDir dir;
  const std::string dem = (test::sourceDir() / "samples/terrain/mount_st_helens.dem").string();
  auto scene = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return quote(dir / name);
  };
  const std::string obj = "{\"objects\": [{\"dem\": \"" + dem + "\"";
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.2\nf 1 2 3\nf 1 3 4\n";
  struct Case {
    std::string args;
    std::vector<std::string> expect;  // every part must be in the one-line message
  };
  const Case cases[] = {
      {scene("bad.json", "{ \"objects\": [ }"), {"bad.json", "not valid JSON"}},
      {quote(dir / "absent.json"), {"absent.json", "no such file"}},
      {scene("unknown.json", obj + ", \"lines\": {\"curve_factr\": 1}}]}"),
       {"objects.0.lines.curve_factr", "unknown key", "curve_factor"}},
      {scene("range.json", obj + ", \"lines\": {\"curve_factor\": 500}}]}"),
       {"objects.0.lines.curve_factor", "500", "[0, 100]"}},
      {scene("type.json", obj + ", \"shading\": {\"sigma\": \"wide\"}}]}"),
       {"objects.0.shading.sigma", "expected a number"}},
      {scene("order.json", obj + ", \"shading\": {\"thresholds\": [0.5, 0.2, 0.6, 0.7]}}]}"),
       {"objects.0.shading.thresholds", "ascending"}},
      {scene("count.json", obj + ", \"shading\": {\"tones\": [0.1, 0.2]}}]}"),
       {"objects.0.shading.tones", "list of 5"}},
      {scene("choice.json", obj + ", \"lines\": {\"curvature\": \"jet\"}}]}"),
       {"objects.0.lines.curvature", "quadric, cotangent, screen"}},
      {scene("none.json", "{\"objects\": []}"), {"objects", "needs at least 1 entry"}},
      {scene("both.json", obj + ", \"mesh\": \"a.obj\"}]}"), {"objects.0", "both 'mesh' and 'dem'"}},
      {scene("missing.json", "{\"objects\": [{\"mesh\": \"nowhere.obj\"}]}"), {"objects.0.mesh", "nowhere.obj"}},
      {scene("tex.json", obj + ", \"wrinkle\": {\"texture\": \"nowhere.png\", \"uv\": \"planar\"}}]}"),
       {"objects.0.wrinkle.texture", "nowhere.png"}},
      {scene("uv.json", "{\"objects\": [{\"mesh\": \"" + (dir / "quad.obj").string() +
                            "\", \"wrinkle\": {\"texture\": \"" +
                            (test::sourceDir() / "samples/textures/rain_strokes_wrinkle.png").string() + "\"}}]}"),
       {"objects.0.wrinkle.uv", "no UVs"}},
      {scene("light.json", obj + "}], \"light\": {\"direction\": [0, 0, 0]}}"), {"light.direction", "zero"}},
      {scene("elev.json", obj + "}], \"camera\": {\"elevation\": 90}}"), {"camera.elevation", "89.9"}},
      {scene("diff.json", obj + "}], \"diffusion\": {\"iterations\": 5000}}"), {"diffusion.iterations", "[0, 1000]"}},
      {sampleScene() + " --set objects.3.lines.curve_factor=2", {"--set", "objects.3", "the list has 1"}},
      {sampleScene() + " --set nonsense", {"--set", "KEY=VALUE"}},
      {sampleScene() + " --set output.width=0", {"output.width", "[1, 16384]"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const auto r = run(bin("shanshui-render") + " " + c.args + " -o " + quote(dir / "out.png"));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(lineCount(r.output), 1) << r.output;
    for (const std::string& part : c.expect)
      EXPECT_NE(r.output.find(part), std::string::npos) << part << " in " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
  }
}

}  // namespace
}  // namespace shanshui
