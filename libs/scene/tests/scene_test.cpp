// Scene files: defaults, round trips, overrides, the schema against docs/scene.md, errors.
#include "shanshui/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "shanshui/scene/scene_assets.h"
#include "test_support.h"

namespace shanshui::scene {
namespace {

using nlohmann::json;

const json kMinimal = {{"objects", json::array({{{"dem", "hill.asc"}}})}};

std::string errorOf(const json& j) {
  try {
    parseScene(j, "s.json", ".");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, MissingKeysTakeTheDocumentedDefaults) {
  const Scene s = parseScene(kMinimal, "s.json", "base");
  ASSERT_EQ(s.objects.size(), 1u);
  const Object& o = s.objects[0];
  const Object d;
  EXPECT_EQ(o.dem, "hill.asc");
  EXPECT_EQ(o.name, "objects.0");
  EXPECT_EQ(o.lines.curve_factor, d.lines.curve_factor);
  EXPECT_EQ(o.shading.tones, d.shading.tones);
  EXPECT_EQ(o.shading.beta, -1.0);
  EXPECT_EQ(s.output.width, 1024);
  EXPECT_FALSE(s.camera.target.has_value());
  EXPECT_FALSE(s.diffusion.enabled());
  EXPECT_EQ(s.resolve("hill.asc"), std::filesystem::path("base") / "hill.asc");
  EXPECT_FALSE(s.usesWrinkles());
  EXPECT_TRUE(s.usesLines());
}

TEST(Scene, SampleSceneRoundTripsThroughJson) {
  const Scene a = loadScene(test::sourceDir() / "samples/scenes/default.json");
  const json ja = toJson(a);
  const Scene b = parseScene(ja, "again", a.base_dir);
  EXPECT_EQ(toJson(b), ja);
  EXPECT_TRUE(a.usesWrinkles());
  EXPECT_EQ(a.camera.path.size(), 3u);
  // Non-default values survive too.
  json j = ja;
  j["objects"][0]["lines"]["curvature"] = "screen";
  j["camera"]["target"] = {1, 2, 3};
  j["objects"][0]["transform"]["rotate"] = {0, 0, 45};
  j["canvas"] = {{"type", "static"}, {"static_pattern", "silk"}, {"impulses", 16}, {"isotropic", true}};
  const Scene c = parseScene(j, "c", ".");
  EXPECT_EQ(c.canvas.type, CanvasType::Static);
  EXPECT_EQ(c.canvas.pattern(), CanvasPattern::Silk);
  EXPECT_EQ(c.canvas.impulses, 16);
  EXPECT_EQ(c.objects[0].lines.curvature, CurvatureSource::Screen);
  EXPECT_EQ(*c.camera.target, glm::dvec3(1, 2, 3));
  EXPECT_EQ(toJson(parseScene(toJson(c), "d", ".")), toJson(c));
}

TEST(Scene, SavedScenesLoadBackTheSame) {
  test::TempDir dir;
  Scene s = loadScene(test::sourceDir() / "samples/scenes/default.json", {"objects.0.lines.curve_factor=1.25"});
  s.base_dir = dir.path();
  s.objects[0].dem = (test::sourceDir() / "samples/terrain/mount_st_helens.dem").string();
  saveScene(s, dir / "saved.json");
  const Scene back = loadScene(dir / "saved.json");
  json a = toJson(back), b = toJson(s);
  a["objects"][0].erase("dem");  // written relative to the saved file
  b["objects"][0].erase("dem");
  EXPECT_EQ(a, b);
  EXPECT_TRUE(std::filesystem::equivalent(back.resolve(back.objects[0].dem), s.objects[0].dem));
  EXPECT_EQ(back.objects[0].lines.curve_factor, 1.25);
  EXPECT_THROW(saveScene(s, dir / "no_such_dir" / "x.json"), Error);
  // Relative paths follow the file: saved elsewhere, the scene still finds its inputs.
  const Scene sample = loadScene(test::sourceDir() / "samples/scenes/default.json");
  std::filesystem::create_directories(dir / "deeper" / "still");
  saveScene(sample, dir / "deeper" / "still" / "moved.json");
  const Scene moved = loadScene(dir / "deeper" / "still" / "moved.json");
  EXPECT_TRUE(std::filesystem::equivalent(moved.resolve(moved.objects[0].dem), sample.resolve(sample.objects[0].dem)));
  EXPECT_TRUE(std::filesystem::equivalent(moved.resolve(moved.objects[0].wrinkle.texture),
                                          sample.resolve(sample.objects[0].wrinkle.texture)));
}

TEST(Scene, OverridesTakeDottedPathsAndJsonValues) {
  json j = kMinimal;
  applyOverride(j, "objects.0.lines.curve_factor=2.5");
  applyOverride(j, "objects.0.shading.tones=[0.1,0.2,0.3,0.4,0.5]");
  applyOverride(j, "objects.0.lines.enabled=false");
  applyOverride(j, "canvas.type=none");  // not JSON: a string
  applyOverride(j, "objects.0.name=\"peak\"");
  const Scene s = parseScene(j, "s", ".");
  EXPECT_EQ(s.objects[0].lines.curve_factor, 2.5);
  EXPECT_EQ(s.objects[0].shading.tones[4], 0.5);
  EXPECT_FALSE(s.objects[0].lines.enabled);
  EXPECT_EQ(s.objects[0].name, "peak");
  EXPECT_THROW(applyOverride(j, "objects.1.name=x"), Error);
  EXPECT_THROW(applyOverride(j, "objects.x.name=x"), Error);
  EXPECT_THROW(applyOverride(j, "=3"), Error);
  EXPECT_THROW(applyOverride(j, "objects..name=3"), Error);
  EXPECT_THROW(applyOverride(j, "objects.0.lines.curve_factor.x=3"), Error);  // parent is a number
}

TEST(Scene, EveryKindOfBadValueNamesItsKeyPath) {
  auto with = [](const std::string& path, const json& v) {
    json j = kMinimal;
    j["objects"][0]["wrinkle"] = json::object();
    json* node = &j;
    std::stringstream ss(path);
    std::string part;
    while (std::getline(ss, part, '.')) {
      node = node->is_array() ? &(*node)[std::stoul(part)] : &(*node)[part];
    }
    *node = v;
    return errorOf(j);
  };
  struct Case {
    std::string path;
    json value;
    std::string expect;
  };
  const Case cases[] = {
      {"objects.0.lines.curve_factor", -1, "out of range"},
      {"objects.0.lines.curve_factor", "big", "expected a number"},
      {"objects.0.lines.enabled", 1, "expected true or false"},
      {"objects.0.lines.line_color", json::array({1, 2, 3}), "out of range"},
      {"objects.0.lines.line_color", json::array({1, 1}), "list of 3"},
      {"objects.0.lines", 3, "expected an object"},
      {"objects.0.wrinkle.uv", "cylinder", "not one of"},
      {"objects.0.wrinkle.filter", "anisotropic", "not one of"},
      {"objects.0.max_vertices", 2.5, "expected an integer"},
      {"objects.0.z_scale", 0, "out of range; expected (0, 1000]"},
      {"objects.0.transform.scale", json::array({1, 0, 1}), "objects.0.transform.scale.1"},
      {"objects.0.colour", 1, "unknown key"},
      {"objects", 3, "expected a list"},
      {"camera.path", json::array({{{"zoom", 0}}}), "camera.path.0.zoom"},
      {"objects.0.path", json::array({{{"time", 1}}, {{"time", 1}}}), "key 1's time 1.000000 must be later"},
      {"objects.0.path", json::array({{{"offset", {0, "up", 0}}}}), "objects.0.path.0.offset.1"},
      {"objects.0.path", json::array({{{"time", 1}}}), "at least two keys"},
      {"output.paper", json::array({0.5, 0.5, 1.5}), "output.paper.2"},
      {"seed", -1, "seed"},
      {"canvas.type", "linen", "not one of: none, rice_paper, silk, static"},
      {"canvas.impulses", 0.5, "out of range; expected [1, 1024]"},
      {"canvas.grain", 0, "out of range"},
      {"canvas.static_pattern", "none", "not one of: rice_paper, silk"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.path);
    const std::string e = with(c.path, c.value);
    EXPECT_NE(e.find("s.json: "), std::string::npos) << e;
    EXPECT_NE(e.find(c.path), std::string::npos) << e;
    EXPECT_NE(e.find(c.expect), std::string::npos) << e;
  }
}

// The path's offset against the piecewise-linear interpolation worked by hand, held at
// both ends.
TEST(Scene, AnObjectsPathIsLinearBetweenKeysAndHeldBeyondThem) {
  json j = kMinimal;
  j["objects"][0]["path"] = json::array({{{"time", 1.0}, {"offset", {2, 0, 0}}},
                                         {{"time", 3.0}, {"offset", {2, 4, 0}}},
                                         {{"time", 4.0}, {"offset", {0, 4, -1}}}});
  const Scene s = parseScene(j, "s.json", ".");
  const Object& o = s.objects[0];
  EXPECT_TRUE(o.animated());
  const auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(o.pathOffset(-5.0), {2, 0, 0}));
  EXPECT_TRUE(near(o.pathOffset(1.0), {2, 0, 0}));
  EXPECT_TRUE(near(o.pathOffset(1.5), {2, 1, 0}));
  EXPECT_TRUE(near(o.pathOffset(3.0), {2, 4, 0}));
  EXPECT_TRUE(near(o.pathOffset(3.25), {1.5, 4, -0.25}));
  EXPECT_TRUE(near(o.pathOffset(9.0), {0, 4, -1}));
}

TEST(Scene, AtMost255Objects) {
  json j = {{"objects", json::array()}};
  for (int i = 0; i < 256; ++i) j["objects"].push_back({{"mesh", "m.obj"}});
  EXPECT_NE(errorOf(j).find("at most 255"), std::string::npos) << errorOf(j);
  j["objects"].erase(255);
  EXPECT_EQ(errorOf(j), "");
}

TEST(Scene, DocsTablesAreTheDescriptions) {
  std::ifstream in(test::sourceDir() / "docs/scene.md");
  ASSERT_TRUE(in) << "docs/scene.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  ASSERT_GT(sceneSchema().size(), 50u);
  EXPECT_EQ(spliceDescription(doc, "docs/scene.md"), doc)
      << "docs/scene.md's key tables differ from the description: run "
         "shanshui-render --describe-into docs/scene.md";
  // Every key appears in a table, with every choice.
  for (const SchemaEntry& e : sceneSchema()) {
    const std::string key = e.path.substr(e.table.empty() ? 0 : e.table.size() + 1);
    std::string shown = key;
    for (std::size_t at; (at = shown.find('*')) != std::string::npos;) shown.replace(at, 1, "N");
    EXPECT_NE(doc.find("| `" + shown + "` |"), std::string::npos) << e.path;
    for (const auto& c : e.choices) EXPECT_NE(doc.find("`" + c + "`"), std::string::npos) << e.path << " = " << c;
  }
}

TEST(Scene, SpliceNamesAMissingTable) {
  EXPECT_THROW(spliceDescription("# nothing here\n", "x.md"), Error);
  try {
    spliceDescription("<!-- keys: (top level) -->\n", "x.md");
    ADD_FAILURE() << "a table without its end marker was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x.md"), std::string::npos) << e.what();
  }
}

TEST(Scene, EveryKeyHasMeaningAndDefault) {
  for (const SchemaEntry& e : sceneSchema()) {
    SCOPED_TRACE(e.path);
    EXPECT_FALSE(e.doc.empty());
    EXPECT_FALSE(e.default_text.empty());
    EXPECT_FALSE(e.range_text.empty());
  }
}

TEST(Scene, ParameterHashFollowsTheValues) {
  const Scene a = parseScene(kMinimal, "s", ".");
  Scene b = a;
  EXPECT_EQ(parameterHash(a), parameterHash(b));
  b.objects[0].lines.curve_factor += 1e-9;
  EXPECT_NE(parameterHash(a), parameterHash(b));
  // A uniform changes the full hash but not the rebuild hash; a rebuild key changes both.
  EXPECT_EQ(parameterHash(a, Effect::Rebuild), parameterHash(b, Effect::Rebuild));
  b = a;
  b.canvas.type = CanvasType::Silk;
  EXPECT_NE(parameterHash(a, Effect::Rebuild), parameterHash(b, Effect::Rebuild));
  EXPECT_EQ(parameterHash(a, Effect::Uniform), parameterHash(b, Effect::Uniform));
  b = a;
  b.objects.push_back(b.objects[0]);
  EXPECT_NE(parameterHash(a, Effect::Rebuild), parameterHash(b, Effect::Rebuild));
}

TEST(Scene, RebuildKeysAreTheOnesThatChangeVariantsOrFiles) {
  // The renderer's structure depends on exactly these; a key marked live that changes a
  // shader variant would leave a stale renderer in the viewer.
  std::set<std::string> rebuild;
  for (const SchemaEntry& e : sceneSchema()) {
    if (e.effect == Effect::Rebuild) rebuild.insert(e.path);
  }
  const std::set<std::string> expected = {
      "objects", "objects.*.mesh", "objects.*.dem", "objects.*.z_scale", "objects.*.max_vertices",
      "objects.*.cell_size", "objects.*.fill_nodata", "objects.*.smooth_steps", "objects.*.upsample",
      "objects.*.subdivide", "objects.*.crop", "objects.*.crease_angle", "objects.*.up", "objects.*.recentre",
      "objects.*.lines.enabled", "objects.*.lines.curvature", "objects.*.lines.smoothing", "objects.*.shading.enabled",
      "objects.*.wrinkle.texture", "objects.*.wrinkle.uv", "objects.*.wrinkle.mapping",
      "objects.*.strokes.style",  // builds the strokes pass
      "objects.*.pigment.name",   // builds the pigment pass
      // Elements are placed on load from these (and build
      // the elements pass).
      "objects.*.trees.enabled", "objects.*.trees.density", "objects.*.trees.size", "objects.*.trees.size_spread",
      "objects.*.trees.max_slope", "objects.*.trees.band", "objects.*.trees.open", "objects.*.trees.grove",
      "objects.*.trees.grove_radius", "objects.*.trees.kinds", "objects.*.trees.seed", "objects.*.trees.massed_beyond",
      "objects.*.dots.enabled", "objects.*.dots.density", "objects.*.dots.cluster", "objects.*.dots.spread",
      "objects.*.dots.at_trees", "objects.*.dots.seed", "objects.*.dots.massed_beyond", "objects.*.ground.on",
      "objects.*.marks.style",
      "objects.*.marks.wash",  // 0 or not: the wet strokes' code (WASH)
      "shadow.pigment.name",   // builds the shadow pass
      "substrate.enabled",     // builds the substrate pass
      "substrate.texture",     // a file
      "edges.enabled",         // builds the edges pass
      "motion_blur.enabled",   // velocity target, blur pass
      "water.enabled",         // the water code in the ink pass
      "canvas.type", "canvas.static_pattern", "canvas.method"};
  EXPECT_EQ(rebuild, expected);
}

TEST(Scene, DiffusionRangesAreTheCpuReferences) {
  // The scene parser and ink::validate accept and refuse the same values.
  for (const SchemaEntry& e : sceneSchema()) {
    if (e.path.rfind("diffusion.", 0) != 0) continue;
    SCOPED_TRACE(e.path);
    const std::string key = e.path.substr(10);
    for (double v : {e.min, e.max, e.min - 1, e.max + 1}) {
      json j = kMinimal;
      j["diffusion"][key] = e.kind == "integer" ? json(static_cast<long long>(v)) : json(v);
      bool scene_ok = true;
      try {
        const Scene s = parseScene(j, "s", ".");
        ink::validate(s.diffusion);
      } catch (const Error&) {
        scene_ok = false;
      }
      ink::DiffusionOptions o;
      if (key == "ring_steps") o.ring_steps = static_cast<int>(v);
      if (key == "attenuation") o.attenuation = v;
      if (key == "absorb") o.absorb = v;
      if (key == "residual") o.residual = v;
      if (key == "iterations") o.iterations = static_cast<int>(v);
      if (key == "threshold") o.threshold = v;
      bool ink_ok = true;
      try {
        ink::validate(o);
      } catch (const Error&) {
        ink_ok = false;
      }
      EXPECT_EQ(scene_ok, ink_ok) << v;
      EXPECT_EQ(ink_ok, v >= e.min && v <= e.max) << v;
    }
  }
}

TEST(Scene, SchemaRangesMatchTheParser) {
  // For every bounded number and integer outside lists: both ends parse (an open lower end
  // does not), just outside them does not.
  int checked = 0;
  for (const SchemaEntry& e : sceneSchema()) {
    if ((e.kind != "number" && e.kind != "integer") || e.path.find('*') != std::string::npos) continue;
    SCOPED_TRACE(e.path);
    auto parses = [&](double v) {
      json j = kMinimal;
      applyOverride(
          j, e.path + "=" + (e.kind == "integer" ? std::to_string(static_cast<long long>(v)) : std::to_string(v)));
      try {
        parseScene(j, "s", ".");
        return true;
      } catch (const Error&) {
        return false;
      }
    };
    const double step = std::max(1.0, std::abs(e.max));
    EXPECT_TRUE(parses(e.max)) << e.max;
    EXPECT_FALSE(parses(e.max + step)) << e.max + step;
    EXPECT_EQ(parses(e.min), !e.lo_open) << e.min;
    EXPECT_FALSE(parses(e.min - std::max(1.0, std::abs(e.min)))) << e.min;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(Scene, AMeshOrDemBecomesAOneObjectScene) {
  const Scene s = loadSceneInput("peaks/hill.asc", {"objects.0.z_scale=2"});
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].dem, "peaks/hill.asc");
  EXPECT_EQ(s.objects[0].z_scale, 2.0);
  EXPECT_EQ(loadSceneInput("m.obj").objects[0].mesh, "m.obj");
  EXPECT_THROW(loadSceneInput("notes.txt"), Error);
}

// An ESRI ASCII grid of `columns` x `rows` cells `cell` metres across (projected: corner at
// 0, 0), its height a function of the column and the row.
void writeGrid(const std::filesystem::path& path, int columns, int rows, double cell,
               const std::function<double(int, int)>& height) {
  std::ofstream out(path);
  out << "ncols " << columns << "\nnrows " << rows << "\nxllcorner 0\nyllcorner 0\ncellsize " << cell
      << "\nNODATA_value -9999\n";
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) out << height(c, r) << (c + 1 < columns ? " " : "\n");
  }
}

// The same, its height a function of the column only.
void writeGrid(const std::filesystem::path& path, int columns, int rows, double cell, double (*height)(int)) {
  writeGrid(path, columns, rows, cell, [height](int c, int) { return height(c); });
}

// A lone DEM as a painter takes it: a coast 100 km wide rising from -500 m to 1500 m (relief
// 1:50, a quarter of it under the sea) is raised five times, to 1:10, and its sea becomes
// water at 0 m: 500 of the 2000 m from its lowest point, and 0.2 % above so that a sea
// stored as 0 m lies under it. A steep hill above the sea gets neither, but trees and dots,
// being small; overrides win, and what they changed is not said.
TEST(Scene, ALoneDemFlatterThanOneInTenIsRaisedAndItsSeaBecomesWater) {
  test::TempDir dir;
  writeGrid(dir / "coast.asc", 100, 80, 1000.0, [](int c) { return -500.0 + 2000.0 * c / 99.0; });
  std::vector<std::string> notes;
  const Scene coast = loadSceneInput(dir / "coast.asc", {}, &notes);
  EXPECT_NEAR(coast.objects[0].z_scale, 0.1 / (2000.0 / 100000.0), 1e-9);
  EXPECT_TRUE(coast.water.enabled);
  EXPECT_NEAR(coast.water.level, 500.0 / 2000.0 + 0.002, 1e-9);
  // 100 samples across: made finer until it has 400 (99 · 5 + 1 = 496).
  EXPECT_EQ(coast.objects[0].upsample, 5);
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_NE(notes[0].find("raised 5 times"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("25 % of it at or below 0 m is sea"), std::string::npos) << notes[1];
  EXPECT_NE(notes[2].find("100 x 80 samples: made 5 times finer"), std::string::npos) << notes[2];

  notes.clear();
  const Scene kept =
      loadSceneInput(dir / "coast.asc", {"objects.0.z_scale=1", "water.enabled=false", "objects.0.upsample=1"}, &notes);
  EXPECT_EQ(kept.objects[0].upsample, 1);
  EXPECT_EQ(kept.objects[0].z_scale, 1.0);
  EXPECT_FALSE(kept.water.enabled);
  EXPECT_TRUE(notes.empty()) << notes.front();

  writeGrid(dir / "hill.asc", 50, 50, 10.0, [](int c) { return 100.0 + 300.0 * c / 49.0; });
  const Scene hill = loadSceneInput(dir / "hill.asc", {}, &notes);
  EXPECT_EQ(hill.objects[0].z_scale, 1.0) << "relief 300 m over 500 m";
  EXPECT_FALSE(hill.water.enabled) << "no sea";
  // Half a kilometre across, it grows trees and dots at their real size; the coast, 100 km
  // across, none.
  EXPECT_TRUE(hill.objects[0].trees.enabled && hill.objects[0].dots.enabled);
  EXPECT_FALSE(coast.objects[0].trees.enabled || coast.objects[0].dots.enabled);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_NE(notes[0].find("trees and moss dots grown"), std::string::npos) << notes[0];
  EXPECT_EQ(hill.objects[0].upsample, 8) << "50 samples across: the most, 393";
  notes.clear();
  loadSceneInput(dir / "hill.asc", {"objects.0.trees.enabled=false", "objects.0.upsample=2"}, &notes);
  EXPECT_TRUE(notes.empty()) << notes.front();
  // A flat plain is raised no more than 20 times; a file that does not load is left for the
  // asset cache to report, with the plain look.
  writeGrid(dir / "plain.asc", 100, 100, 1000.0, [](int c) { return 10.0 + 0.01 * c; });
  EXPECT_EQ(loadSceneInput(dir / "plain.asc").objects[0].z_scale, 20.0);
  EXPECT_EQ(loadSceneInput(dir / "missing.asc").objects[0].z_scale, 1.0);
}

// Land below sea level is sea only where it is open to the grid's edge. A basin 86 m deep
// ringed by mountains (Death Valley's Badwater) stays dry and says so; the same basin with a
// channel at 0 m to the edge, or with its sea stored as no data along the edge, is sea. The
// counts are the cells the closed form of each grid gives: a disc of radius 15 cells, 709 of
// the 3600, and the channel's 15.
TEST(Scene, LandBelowSeaLevelIsSeaOnlyWhereItIsOpenToTheEdge) {
  test::TempDir dir;
  auto basin = [](int c, int r, bool channel, bool nodata_edge) {
    const double d = std::hypot(c - 30.0, r - 30.0);
    if (nodata_edge && (c == 0 || r == 0 || c == 59 || r == 59)) return -9999.0;
    if (channel && r == 30 && c < 30) return d <= 15.0 ? -86.0 : 0.0;
    return d <= 15.0 ? -86.0 : 40.0 * (d - 15.0);
  };
  writeGrid(dir / "closed.asc", 60, 60, 100.0, [&](int c, int r) { return basin(c, r, false, false); });
  std::vector<std::string> notes;
  const Scene closed = loadSceneInput(dir / "closed.asc", {}, &notes);
  EXPECT_FALSE(closed.water.enabled);
  const auto dry = std::find_if(notes.begin(), notes.end(), [](const std::string& n) {
    return n.find("basins closed from its edges") != std::string::npos;
  });
  ASSERT_NE(dry, notes.end()) << ::testing::PrintToString(notes);
  EXPECT_NE(dry->find("20 %"), std::string::npos) << *dry;  // 709 of 3600 cells
  EXPECT_NE(dry->find("water.enabled=true"), std::string::npos) << *dry;
  notes.clear();
  EXPECT_TRUE(loadSceneInput(dir / "closed.asc", {"water.enabled=true"}, &notes).water.enabled);
  for (const std::string& n : notes) EXPECT_EQ(n.find("basins closed"), std::string::npos) << n;

  writeGrid(dir / "channel.asc", 60, 60, 100.0, [&](int c, int r) { return basin(c, r, true, false); });
  notes.clear();
  const Scene open = loadSceneInput(dir / "channel.asc", {}, &notes);
  EXPECT_TRUE(open.water.enabled);
  const auto sea = std::find_if(notes.begin(), notes.end(),
                                [](const std::string& n) { return n.find("is sea") != std::string::npos; });
  ASSERT_NE(sea, notes.end()) << ::testing::PrintToString(notes);
  EXPECT_NE(sea->find("20 %"), std::string::npos) << *sea;  // 709 + 15 of 3600 cells

  writeGrid(dir / "nodata.asc", 60, 60, 100.0, [&](int c, int r) { return basin(c, r, true, true); });
  EXPECT_TRUE(loadSceneInput(dir / "nodata.asc").water.enabled) << "the channel reaches the edge's no data";
}

// An OBJ of `n` x `n` vertices `cell` apart, the height `height(i, j)` along `up` (0: x, 1:
// y, 2: z), the other two axes across; its faces wound so that their normals point up.
void writeLandObj(const std::filesystem::path& path, int n, double cell, int up, double (*height)(int, int)) {
  std::ofstream out(path);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      double v[3];
      v[up] = height(i, j);
      v[(up + 1) % 3] = i * cell;
      v[(up + 2) % 3] = j * cell;
      out << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
    }
  }
  for (int j = 0; j + 1 < n; ++j) {
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;  // (i, j), (i+1, j), (i, j+1), (i+1, j+1)
      out << "f " << a << " " << b << " " << d << "\nf " << a << " " << d << " " << c << "\n";
    }
  }
}

// A lone input is read once: the asset cache meshes what loadSceneInput read for its
// proportions, so by then the file may be gone (a DEM and an OBJ), and the mesh is the one a
// fresh read gives. Read with other options (a --set that changes its sampling), the file is
// read again, and its absence is an error naming it.
TEST(Scene, ALoneInputIsReadOnceForItsLookAndItsMesh) {
  test::TempDir dir;
  auto sameAsAFreshRead = [&](const std::filesystem::path& file) {
    AssetCache fresh;
    const std::vector<glm::dvec3> expected = fresh.get(loadSceneInput(file), 0).geometry->mesh.positions;
    AssetCache cache;
    const Scene s = loadSceneInput(file, {}, nullptr, &cache);
    std::filesystem::remove(file);
    EXPECT_EQ(cache.get(s, 0).geometry->mesh.positions, expected) << file;
  };
  auto hill = [&] { writeGrid(dir / "hill.asc", 50, 40, 10.0, [](int c) { return 100.0 + 300.0 * c / 49.0; }); };
  hill();
  sameAsAFreshRead(dir / "hill.asc");
  writeLandObj(dir / "land.obj", 21, 100.0, 2, [](int i, int j) { return 30.0 * i * j / 400.0; });
  sameAsAFreshRead(dir / "land.obj");

  hill();
  AssetCache cache;
  const Scene coarser = loadSceneInput(dir / "hill.asc", {"objects.0.max_vertices=500"}, nullptr, &cache);
  std::filesystem::remove(dir / "hill.asc");
  try {
    cache.get(coarser, 0);
    ADD_FAILURE() << "the file, read ahead with other options, was not read again";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hill.asc"), std::string::npos) << e.what();
  }
}

// A DEM in whole metres is drawn smoothed within half a metre of what it stores, unless
// `smooth_steps` is off (a model of terraces): then every vertex is at its sample's stored
// height, found from the function that wrote the file.
TEST(Scene, SmoothStepsOffKeepsTheHeightsTheFileStores) {
  test::TempDir dir;
  const int n = 41;
  auto stored = [](int c, int r) {
    return std::round(100.0 + 40.0 * std::exp(-((c - 20.0) * (c - 20.0) + (r - 18.0) * (r - 18.0)) / 150.0));
  };
  writeGrid(dir / "hill.asc", n, n, 10.0, stored);
  // The worst distance of a vertex from its sample's stored height, and the mean.
  auto fromStored = [&](bool smooth) {
    nlohmann::json j = {{"objects", {{{"dem", "hill.asc"}, {"recentre", false}, {"smooth_steps", smooth}}}}};
    const Scene s = parseScene(j, "s.json", dir.path().string());
    AssetCache cache;
    const std::vector<glm::dvec3>& p = cache.get(s, 0).geometry->mesh.positions;
    EXPECT_EQ(p.size(), static_cast<std::size_t>(n * n)) << "every sample a vertex";
    glm::dvec2 low(1e300);
    for (const glm::dvec3& v : p) low = glm::min(low, glm::dvec2(v));
    double worst = 0.0, sum = 0.0;
    for (const glm::dvec3& v : p) {
      const int c = static_cast<int>(std::lround((v.x - low.x) / 10.0));
      const int r = n - 1 - static_cast<int>(std::lround((v.y - low.y) / 10.0));  // rows run north to south
      const double d = std::abs(v.z - stored(c, r));
      worst = std::max(worst, d);
      sum += d;
    }
    return std::make_pair(worst, sum / static_cast<double>(p.size()));
  };
  const auto [kept_worst, kept_mean] = fromStored(false);
  EXPECT_LT(kept_worst, 1e-9) << "smooth_steps false keeps the file's values";
  const auto [smoothed_worst, smoothed_mean] = fromStored(true);
  EXPECT_LE(smoothed_worst, 0.5 + 1e-9) << "within half a step of what the file stores";
  EXPECT_GT(smoothed_mean, 0.05) << "the staircase was smoothed";
}

// objects.N.upsample meshes the grid that many times finer: (n − 1)·f + 1 vertices a side,
// those over a stored sample at its height, within max_vertices (the most factor that fits
// is taken); the cubic between them follows a bowl (a quadratic, which Catmull-Rom
// reproduces) to rounding, where the coarse mesh's flat triangles miss by up to a quarter
// of its curvature times a cell squared.
TEST(Scene, UpsampleMeshesTheGridFinerWithinTheVertices) {
  test::TempDir dir;
  const int n = 21;
  auto bowl = [](double x, double y) { return 0.01 * ((x - 95.0) * (x - 95.0) + (y - 80.0) * (y - 80.0)); };
  writeGrid(dir / "bowl.asc", n, n, 10.0, [&](int c, int r) { return bowl(10.0 * c, 10.0 * (n - 1 - r)); });
  auto mesh = [&](int upsample, int max_vertices) {
    nlohmann::json j = {{"objects",
                         {{{"dem", "bowl.asc"},
                           {"recentre", false},
                           {"smooth_steps", false},  // its heights lie on a lattice of whole metres and quarters
                           {"upsample", upsample},
                           {"max_vertices", max_vertices}}}}};
    AssetCache cache;
    return cache.get(parseScene(j, "s.json", dir.path().string()), 0).geometry->mesh.positions;
  };
  const std::vector<glm::dvec3> fine = mesh(3, 250000);
  ASSERT_EQ(fine.size(), static_cast<std::size_t>(61 * 61));
  glm::dvec2 low(1e300);
  for (const glm::dvec3& v : fine) low = glm::min(low, glm::dvec2(v));
  double worst = 0.0;
  for (const glm::dvec3& v : fine) worst = std::max(worst, std::abs(v.z - bowl(v.x - low.x, v.y - low.y)));
  EXPECT_LT(worst, 1e-6) << "the bowl, between the samples too";
  EXPECT_EQ(mesh(3, 1000).size(), static_cast<std::size_t>(21 * 21)) << "2 x (41² = 1681) is over 1000 too";
  EXPECT_EQ(mesh(3, 2000).size(), static_cast<std::size_t>(41 * 41)) << "the most that fits";
  nlohmann::json bad = {{"objects", {{{"dem", "bowl.asc"}, {"upsample", 9}}}}};
  EXPECT_THROW(parseScene(bad, "s.json", dir.path().string()), Error);
}

// A lone mesh that is a piece of land (open, flat along its up axis, facing up) is painted
// as a DEM is, raised when flatter than 1:10 (its transform's scale along z, the axis up once
// loaded) and wooded when small; a closed flat box (a boulder, a plinth) stays an object. The
// formats people bring are taken alone (glTF, an SRTM tile), anything else is named.
TEST(Scene, ALoneMeshThatIsAPieceOfLandIsPaintedAsLand) {
  test::TempDir dir;
  // 8 km across, z up, relief 400 m: 1:20, raised 2 times.
  writeLandObj(dir / "land.obj", 41, 200.0, 2, [](int i, int j) { return 400.0 * (i / 40.0) * (j / 40.0); });
  std::vector<std::string> notes;
  const Scene land = loadSceneInput(dir / "land.obj", {}, &notes);
  EXPECT_EQ(land.camera.preset, CameraPreset::Deep);
  EXPECT_TRUE(land.objects[0].dissolvesBorder());
  EXPECT_TRUE(land.objects[0].marks.washes());
  EXPECT_TRUE(land.mist.enabled());
  EXPECT_TRUE(land.objects[0].trees.enabled);
  EXPECT_FALSE(land.water.enabled) << "a mesh's heights need not be elevations: no sea";
  EXPECT_NEAR(land.objects[0].transform.scale.z, 0.1 * 8000.0 / 400.0, 1e-9) << "1:20 raised to 1:10";
  EXPECT_EQ(land.objects[0].transform.scale.x, 1.0);
  // 41² = 1681 vertices, under 4000: Loop-subdivided once (6561).
  EXPECT_EQ(land.objects[0].subdivide, 1);
  ASSERT_EQ(notes.size(), 4u);
  EXPECT_NE(notes[0].find("a piece of land (100 % of its surface faces up)"), std::string::npos) << notes[0];
  EXPECT_NE(notes[1].find("objects.0.transform.scale"), std::string::npos) << notes[1];
  EXPECT_NE(notes[3].find("1681 vertices: Loop-subdivided once (objects.0.subdivide)"), std::string::npos) << notes[3];
  AssetCache cache;
  EXPECT_EQ(cache.get(land, 0).geometry->mesh.positions.size(), 6561u) << "a vertex on each of its 4880 edges";
  // Asked for four steps, a land of 199 712 triangles takes one (798 848): a second would
  // make 3.2 million, over the 2 million a scene's subdivision makes.
  writeLandObj(dir / "big.obj", 317, 10.0, 2, [](int i, int j) { return 0.1 * i * j; });
  nlohmann::json big_scene = {{"objects", {{{"mesh", "big.obj"}, {"subdivide", 4}}}}};
  EXPECT_EQ(cache.get(parseScene(big_scene, "s.json", dir.path().string()), 0).geometry->mesh.triangles.size(),
            4u * 199712u);
  notes.clear();
  EXPECT_EQ(loadSceneInput(dir / "land.obj", {"objects.0.subdivide=0"}, &notes).objects[0].subdivide, 0);
  EXPECT_EQ(notes.size(), 3u) << "what the user set is not said";

  // The same land Y up, as glTF writes it: land too.
  writeLandObj(dir / "land_y.obj", 21, 10.0, 1, [](int i, int) { return 30.0 + 2.0 * i; });
  EXPECT_EQ(loadSceneInput(dir / "land_y.obj").camera.preset, CameraPreset::Deep);

  // A closed box 10 x 10 x 2: flat, but half of it faces down.
  {
    std::ofstream box(dir / "box.obj");
    box << "v 0 0 0\nv 10 0 0\nv 10 10 0\nv 0 10 0\nv 0 0 2\nv 10 0 2\nv 10 10 2\nv 0 10 2\n"
           "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
  }
  notes.clear();
  const Scene box = loadSceneInput(dir / "box.obj", {}, &notes);
  EXPECT_EQ(box.camera.preset, CameraPreset::None);
  EXPECT_EQ(box.camera.framing, Framing::Fill);
  EXPECT_FALSE(box.objects[0].dissolvesBorder());
  EXPECT_FALSE(box.objects[0].trees.enabled);
  EXPECT_TRUE(notes.empty());
  // Land as thick as it is wide is not flat, so `auto` takes no axis for it; told its up
  // axis, it is land.
  writeLandObj(dir / "peak.obj", 11, 10.0, 2, [](int i, int j) { return 8.0 * std::min(i, j); });
  EXPECT_EQ(loadSceneInput(dir / "peak.obj").camera.preset, CameraPreset::None);
  EXPECT_EQ(loadSceneInput(dir / "peak.obj", {"objects.0.up=z"}).camera.preset, CameraPreset::Deep);

  EXPECT_EQ(loadSceneInput("ship.glb").objects[0].mesh, "ship.glb");
  EXPECT_EQ(loadSceneInput("N46E007.hgt").objects[0].dem, "N46E007.hgt");
  try {
    loadSceneInput("notes.txt");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(".gltf .glb"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(".hgt"), std::string::npos) << e.what();
  }
}

TEST(Scene, ALoneMeshOrDemGetsTheSampleStyleAndAFramedView) {
  const Scene dem = loadSceneInput("peaks/hill.png");
  const Scene plain = parseScene(kMinimal, "s.json", ".");
  EXPECT_GT(dem.objects[0].lines.width, 0.0) << "strokes, not Eq. 1's bands";
  EXPECT_NE(dem.objects[0].shading.tones, plain.objects[0].shading.tones) << "the sample's tones";
  EXPECT_EQ(dem.canvas.type, CanvasType::RicePaper);
  EXPECT_EQ(dem.camera.preset, CameraPreset::Deep);
  EXPECT_TRUE(dem.mist.enabled());
  EXPECT_TRUE(dem.objects[0].dissolvesBorder());
  EXPECT_TRUE(dem.objects[0].marks.washes()) << "land gets wet strokes";
  EXPECT_GT(dem.objects[0].marks.wash_width, 1.0);
  const Scene mesh = loadSceneInput("teapot.obj", {"camera.elevation=10"});
  EXPECT_EQ(mesh.camera.preset, CameraPreset::None);
  EXPECT_EQ(mesh.camera.framing, Framing::Fill);
  EXPECT_EQ(mesh.camera.elevation_deg, 10.0);
  EXPECT_FALSE(mesh.mist.enabled()) << "mist is a DEM's: it would hide a lone object's foot";
  EXPECT_FALSE(mesh.objects[0].dissolvesBorder());
  EXPECT_FALSE(mesh.objects[0].marks.washes()) << "a lone object may be a building";
  // The defaults of a scene file stay the plain ones.
  EXPECT_EQ(plain.canvas.type, CanvasType::None);
  EXPECT_EQ(plain.camera.preset, CameraPreset::None);
  EXPECT_EQ(plain.camera.framing, Framing::Sphere);
}

TEST(Scene, AVerticalScrollIsTallAndFortyPercentWide) {
  json j = kMinimal;
  j["output"] = {{"width", 900}, {"height", 1000}, {"format", "vertical_scroll"}};
  const Scene s = parseScene(j, "s.json", ".");
  EXPECT_EQ(s.output.pixelHeight(), 1000);
  EXPECT_EQ(s.output.pixelWidth(), 400);
  j["output"]["format"] = "free";
  EXPECT_EQ(parseScene(j, "s.json", ".").output.pixelWidth(), 900);
  j["output"]["format"] = "scroll";
  EXPECT_NE(errorOf(j).find("output.format"), std::string::npos) << errorOf(j);
}

// A cone of height 3 standing on the axis `up` of its file (base radius 1).
mesh::Mesh coneAlong(int up) {
  mesh::Mesh m;
  const int n = 24;
  auto place = [up](double a, double b, double h) {
    glm::dvec3 p;
    p[up] = h;
    p[(up + 1) % 3] = a;
    p[(up + 2) % 3] = b;
    return p;
  };
  for (int i = 0; i < n; ++i) {
    const double t = 2 * 3.14159265358979 * i / n;
    m.positions.push_back(place(std::cos(t), std::sin(t), 0));
  }
  m.positions.push_back(place(0, 0, 3));  // apex
  m.positions.push_back(place(0, 0, 0));  // base centre
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    m.triangles.push_back({i, j, static_cast<std::uint32_t>(n)});
    m.triangles.push_back({j, i, static_cast<std::uint32_t>(n + 1)});
  }
  return m;
}

double signedVolume(const mesh::Mesh& m) {
  double v = 0;
  for (const glm::uvec3& t : m.triangles) {
    v += glm::dot(m.positions[t.x], glm::cross(m.positions[t.y], m.positions[t.z])) / 6.0;
  }
  return v;
}

TEST(SceneAssets, TheUpAxisBecomesZAndMeshesAreYUpByDefault) {
  for (const auto& [file_up, key] :
       std::vector<std::pair<int, std::string>>{{1, "auto"}, {1, "y"}, {0, "x"}, {2, "z"}}) {
    SCOPED_TRACE(key);
    const mesh::Mesh m = coneAlong(file_up);
    json j = {{"objects", json::array({{{"mesh", "cone.obj"}, {"up", key}, {"recentre", false}}})}};
    const ObjectAsset a = prepareAsset(m, parseScene(j, "s.json", ".").objects[0]);
    EXPECT_NEAR(a.bounds.size().z, 3.0, 1e-9);
    EXPECT_NEAR(a.bounds.size().x, 2.0, 1e-9);
    EXPECT_NEAR(a.bounds.size().y, 2.0, 0.02);
    EXPECT_NEAR(a.mesh.positions[24].z, 3.0, 1e-9) << "the apex is on top";
    EXPECT_NEAR(signedVolume(a.mesh), signedVolume(m), 1e-9) << "a rotation: faces keep their winding";
  }
  // A flat piece of land lies on its thin axis whatever its file says.
  mesh::Mesh land;
  land.positions = {{0, 0, 0}, {10, 0.5, 0}, {0, 0.2, 10}, {10, 1, 10}};
  land.triangles = {{0, 1, 2}, {1, 3, 2}};
  json j = {{"objects", json::array({{{"mesh", "land.obj"}, {"recentre", false}}})}};
  const ObjectAsset a = prepareAsset(land, parseScene(j, "s.json", ".").objects[0]);
  EXPECT_NEAR(a.bounds.size().z, 1.0, 1e-9);
}

TEST(SceneAssets, AnImageDemGetsCellsFromItsReliefAndKeepsAGivenCellSize) {
  test::TempDir dir;
  image::Image h(101, 51, 1);
  for (int y = 0; y < h.height; ++y) {
    for (int x = 0; x < h.width; ++x) h.at(x, y, 0) = static_cast<float>((200.0 + 10.0 * x) / 65535.0);
  }
  image::saveImage(h, dir / "ramp.png", image::PixelDepth::UInt16);
  AssetCache cache;
  json j = {{"objects", json::array({{{"dem", "ramp.png"}, {"lines", {{"enabled", false}}}}})}};
  Scene s = parseScene(j, "s.json", dir.path());
  // Relief 1000 over 100 cells: the larger side is 8 times the relief.
  const mesh::Bounds b = cache.get(s, 0).geometry->bounds;
  EXPECT_NEAR(b.size().z, 1000.0, 1e-6);
  EXPECT_NEAR(b.size().x, kImageReliefRatio * 1000.0, 1e-6);
  EXPECT_NEAR(b.size().y, kImageReliefRatio * 1000.0 * 50 / 100, 1e-6);
  s.objects[0].cell_size = 30.0;
  EXPECT_NEAR(cache.get(s, 0).geometry->bounds.size().x, 3000.0, 1e-6);
}

TEST(SceneAssets, EveryComponentOfAMeshIsKeptForRendering) {
  test::TempDir dir;
  std::ofstream(dir / "two.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                    "v 5 0 0\nv 5.2 0 0\nv 5 0.2 0\nv 5 0 0.2\n"
                                    "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"
                                    "f 5 7 6\nf 5 6 8\nf 6 7 8\nf 7 5 8\n";
  AssetCache cache;
  // Smooth normals (crease_angle 180): no vertex is split at the tetrahedra's sharp edges.
  json j = {
      {"objects",
       json::array({{{"mesh", "two.obj"}, {"up", "z"}, {"crease_angle", 180}, {"lines", {{"enabled", false}}}}})}};
  const ObjectAsset& a = *cache.get(parseScene(j, "s.json", dir.path()), 0).geometry;
  EXPECT_EQ(a.mesh.positions.size(), 8u) << "the small lid is drawn too";
  EXPECT_EQ(a.mesh.triangles.size(), 8u);
}

TEST(SceneAssets, PlanarUvsSpanTheLargerExtentAndLumaIsEquationFive) {
  mesh::Mesh m;
  m.positions = {{10, 20, 0}, {14, 20, 5}, {10, 22, 1}};
  m.triangles = {{0, 1, 2}};
  planarUvs(m);
  EXPECT_EQ(m.uvs[0], glm::vec2(0, 0));
  EXPECT_EQ(m.uvs[1], glm::vec2(1, 0));
  EXPECT_EQ(m.uvs[2], glm::vec2(0, 0.5f));
  image::Image rgb(1, 1, 3);
  rgb.pixels = {1.0f, 0.5f, 0.0f};
  EXPECT_FLOAT_EQ(wrinkleLuma(rgb).pixels[0], 0.3f + 0.295f);
}

TEST(SceneAssets, AWrinkledMeshWithoutUvsIsRefusedAndPlanarUvsAreMade) {
  mesh::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.3}};
  m.triangles = {{0, 1, 2}, {1, 3, 2}};
  Object o;
  o.mesh = "quad.obj";
  o.wrinkle.texture = "w.png";
  try {
    prepareAsset(m, o, "objects.0");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("objects.0.wrinkle.uv: quad.obj has no UVs"), std::string::npos) << e.what();
  }
  o.wrinkle.uv = UvSource::Planar;
  const ObjectAsset a = prepareAsset(m, o);
  EXPECT_EQ(a.mesh.uvs.size(), 4u);
  EXPECT_EQ(a.curvature.size(), 4u);
  o.wrinkle.texture.clear();
  o.lines.enabled = false;
  const ObjectAsset b = prepareAsset(m, o);
  EXPECT_TRUE(b.mesh.uvs.empty()) << "no wrinkles: no UVs uploaded";
  EXPECT_TRUE(b.curvature.empty()) << "no lines: no curvature computed";
  EXPECT_EQ(b.feature_size, 0.0);
}

}  // namespace
}  // namespace shanshui::scene
