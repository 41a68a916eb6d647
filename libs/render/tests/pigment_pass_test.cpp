// The pigment pass (issue 25) against the Kubelka–Munk reference on the CPU: each object
// pixel's wash over the ink picture is the reference layer on that picture; the wash follows
// the ink and the atmosphere as its keys say; a scene without pigment builds nothing for it.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "box_on_plane.h"
#include "gl_test.h"
#include "scene_in_memory.h"
#include "shanshui/image/image_io.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/pigment/kubelka_munk.h"
#include "shanshui/pigment/palette.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene_assets.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using nlohmann::json;
using test::prepare;
using test::sceneWith;

class Pigment : public test::HeadlessGl {};

bool contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

TEST_F(Pigment, PassAndVariantAreBuiltOnlyForAScenesPigments) {
  const scene::Scene plain = sceneWith({}), washed = sceneWith({{"pigment", {{"name", "ochre"}}}});
  InkRenderer a(plain, prepare(plain, test::uvSphere(1.0))), b(washed, prepare(washed, test::uvSphere(1.0)));
  EXPECT_FALSE(contains(a.passesBuilt(), "pigment"));
  EXPECT_EQ(a.variants().at("ink").front().find("PIGMENT"), std::string::npos);
  EXPECT_TRUE(contains(b.passesBuilt(), "pigment"));
  EXPECT_NE(b.variants().at("ink").front().find("PIGMENT"), std::string::npos);
  // The wash's texture layer is the G-buffer's erosion noise (SURFACE), sampled there only
  // for a wash: the ink pass samples its own.
  EXPECT_EQ(a.variants().at("gbuffer").front().find("SURFACE"), std::string::npos);
  EXPECT_NE(b.variants().at("gbuffer").front().find("SURFACE"), std::string::npos);
  FrameStats st;
  b.render(sceneCamera(washed, b.worldBounds(), 1.0, {20, 30, 1.0}), 64, 64, &st);
  EXPECT_TRUE(std::any_of(st.passes.begin(), st.passes.end(), [](const PassTime& p) { return p.name == "pigment"; }));
}

// Every object pixel: the reference layer, thickness × the presence the ink pass left in
// alpha, over the ink picture; the background untouched. With the distance fade on, so the
// presence varies across the sphere.
TEST_F(Pigment, WashIsTheKubelkaMunkLayerOverTheInkPicture) {
  const json object = {{"pigment",
                        {{"name", "custom"},
                         {"on_white", {0.85, 0.6, 0.3}},
                         {"on_black", {0.3, 0.1, 0.05}},
                         {"thickness", 0.8},
                         {"follow_ink", 0.0},
                         {"texture", 0.0}}}};
  const scene::Scene s = sceneWith(object, {{"output", {{"fade", 0.8}}}});
  InkRenderer r(s, prepare(s, test::uvSphere(1.0)));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {20, 30, 1.0});
  const image::Image out = r.render(cam, 96, 96).colour(0).download(3);
  const image::Image ink = r.passTarget("ink")->colour(0).download(4);
  const image::Image world = r.worldPositions();
  const pigment::Coefficients c = pigment::coefficients({{0.85, 0.6, 0.3}, {0.3, 0.1, 0.05}});
  double worst = 0.0, change = 0.0, lowest = 1.0, highest = 0.0;
  int objectPixels = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const glm::dvec3 before(ink.at(x, y, 0), ink.at(x, y, 1), ink.at(x, y, 2));
      const glm::dvec3 after(out.at(x, y, 0), out.at(x, y, 1), out.at(x, y, 2));
      if (world.at(x, y, 3) < 0.5) {
        worst = std::max(worst, glm::length(after - before));
        continue;
      }
      const double presence = ink.at(x, y, 3);
      lowest = std::min(lowest, presence);
      highest = std::max(highest, presence);
      const glm::dvec3 expected = pigment::onSubstrate(pigment::layer(c, 0.8 * presence), before);
      for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(after[i] - expected[i]));
      change += glm::length(after - before);
      ++objectPixels;
    }
  ASSERT_GT(objectPixels, 1000);
  EXPECT_LE(worst, 2.5 / 255);
  EXPECT_GT(change / objectPixels, 0.05) << "the wash is visible";
  EXPECT_LT(lowest, highest - 0.1) << "the fade thins the wash across the sphere";
}

// follow_ink 1: bare paper (lit slopes in a light tone ladder) keeps no wash; the ink takes it.
TEST_F(Pigment, AWashThatFollowsTheInkLeavesBarePaperBare) {
  const json object = {{"lines", {{"enabled", false}}},
                       {"shading", {{"tones", {0.3, 0.5, 1.0, 1.0, 1.0}}, {"sigma", 0.0}}},
                       {"pigment", {{"name", "indigo"}, {"thickness", 1.5}, {"follow_ink", 1.0}, {"texture", 0.0}}}};
  const scene::Scene s = sceneWith(object, {{"output", {{"fade", 0.0}}}});
  InkRenderer r(s, prepare(s, test::uvSphere(1.0)));
  const image::Image out = r.render(sceneCamera(s, r.worldBounds(), 1.0, {20, 30, 1.0}), 96, 96).colour(0).download(3);
  const image::Image ink = r.passTarget("ink")->colour(0).download(3);
  const image::Image world = r.worldPositions();
  const glm::dvec3 paper = s.output.paper;
  int bare = 0, inked = 0, bareChanged = 0, inkedChanged = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      if (world.at(x, y, 3) < 0.5) continue;
      const glm::dvec3 before(ink.at(x, y, 0), ink.at(x, y, 1), ink.at(x, y, 2));
      const glm::dvec3 after(out.at(x, y, 0), out.at(x, y, 1), out.at(x, y, 2));
      const double moved = glm::length(after - before);
      if (glm::length(before - paper) < 2.0 / 255) {
        ++bare;
        bareChanged += moved > 1.5 / 255;
      } else if (before.g < 0.5 * paper.g) {
        ++inked;
        inkedChanged += moved > 0.02;
      }
    }
  ASSERT_GT(bare, 200);
  ASSERT_GT(inked, 200);
  EXPECT_EQ(bareChanged, 0);
  EXPECT_EQ(inkedChanged, inked);
}

TEST_F(Pigment, ACustomPigmentThatDoesNotDarkenOnBlackIsRefusedByKey) {
  test::expectErrorNaming(
      [] {
        sceneWith({{"pigment", {{"name", "custom"}, {"on_white", {0.5, 0.5, 0.5}}, {"on_black", {0.2, 0.6, 0.2}}}}});
      },
      "objects.0.pigment.on_black", "channel 1");
}

// A box on a plane, lit from one side: the plane is washed exactly where the ray from it
// towards the light meets the box (the analytic oracle), but at the filtered edge.
TEST_F(Pigment, ShadowWashFallsWhereTheBoxHidesThePlaneFromTheLight) {
  const test::BoxOnPlane box;
  const json j = box.scene(1.0);
  const mesh::Mesh plane = mesh::heightGrid(41, 41, 0.1, [](double, double) { return 0.0; });
  auto loaded = [&](const scene::Scene& s) { return test::BoxOnPlane::load(s, plane); };
  const scene::Scene s = scene::parseScene(j, "test", ".");
  json off = j;
  off.erase("shadow");
  const scene::Scene s0 = scene::parseScene(off, "test", ".");
  InkRenderer r(s, loaded(s)), r0(s0, loaded(s0));
  EXPECT_TRUE(contains(r.passesBuilt(), "shadow"));
  EXPECT_FALSE(contains(r0.passesBuilt(), "shadow"));
  const int size = 256;
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {0, 89, 1.0});
  const image::Image with = r.render(cam, size, size).colour(0).download(3);
  const image::Image world = r.worldPositions();
  const image::Image without = r0.render(cam, size, size).colour(0).download(3);
  int shadowed = 0, wrong = 0, plain = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (world.at(x, y, 3) < 0.5) continue;
      const glm::dvec3 p(world.at(x, y, 0), world.at(x, y, 1), world.at(x, y, 2));
      if (!box.onPlaneBesideBox(p)) continue;
      const bool washed =
          std::abs(with.at(x, y, 0) - without.at(x, y, 0)) + std::abs(with.at(x, y, 2) - without.at(x, y, 2)) > 0.1;
      const bool expected = box.hidden(p);
      shadowed += expected;
      plain += !expected;
      wrong += washed != expected;
    }
  EXPECT_GT(shadowed, 600) << "the box casts a shadow of some size on the plane";
  EXPECT_GT(plain, 20000);
  EXPECT_LE(wrong, shadowed / 20) << "only the filtered edge may disagree";
}

// Seed 000 on a flat wash: a square of even grey (T = 0.6) filling a 256² view from above,
// without a canvas, so the paper's height is the 256² value-noise tile, texel for pixel.
struct FlatWash {
  image::Image out;
  std::vector<double> height;  // per pixel, row 0 at the top
  glm::dvec3 paper;
};

FlatWash flatWash(json substrate, glm::dvec3 light = {-0.5, 0.3, 0.8}, const json& weights = json::object()) {
  substrate["enabled"] = true;
  json object = {
      {"lines", {{"enabled", false}, {"bg_color", {0.6, 0.6, 0.6}}}}, {"shading", {{"enabled", false}}}, {"up", "z"}};
  if (!weights.empty()) object["substrate"] = weights;
  const scene::Scene s = sceneWith(
      object,
      {{"output", {{"fade", 0.0}}}, {"light", {{"direction", {light.x, light.y, light.z}}}}, {"substrate", substrate}});
  const mesh::Mesh square = mesh::heightGrid(33, 33, 1.0 / 32, [](double, double) { return 0.0; });
  InkRenderer r(s, prepare(s, square));
  EXPECT_TRUE(contains(r.passesBuilt(), "substrate"));
  FlatWash w;
  w.out = r.render(sceneCamera(s, r.worldBounds(), 1.0, {0, 90, 1.6}), 256, 256).colour(0).download(3);
  const image::Image world = r.worldPositions();
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) EXPECT_EQ(world.at(x, y, 3), 1.0f) << "the square fills the view";
  // The shader's tile: value noise, seed ^ 0x9A9E5, stored in 8 bits.
  const image::Image noise = noise::erosionNoise(256, s.seed ^ 0x9A9E5ull);
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) w.height.push_back(std::round(noise.at(x, y, 0) * 255.0) / 255.0);
  w.paper = s.output.paper;
  return w;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= a.size();
  mb /= b.size();
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(std::max(saa * sbb, 1e-300));
}

using Substrate = Pigment;

// Dry brush: the bare share of the wash is the share of the paper lying below the
// application a = dry_brush · (1 − ink) (the height's own distribution is the oracle), and
// only pixels below it go bare; a higher threshold bares more.
TEST_F(Substrate, DryBrushBaresThePapersValleysBelowTheThreshold) {
  const double edge = 0.02;
  double last = -1.0;
  for (const double dry : {0.3, 0.6, 0.9}) {
    const FlatWash w = flatWash(
        {{"dry_brush", dry}, {"dry_edge", edge}, {"granulation", 0.0}, {"lighting", 0.0}, {"distortion", 0.0}});
    const double a = dry * 0.6;  // ink = 1 − luma(T) = 0.4
    int bare = 0, below = 0, belowEdge = 0, wrong = 0;
    for (int i = 0; i < 256 * 256; ++i) {
      const bool isBare = std::abs(w.out.pixels[3 * i + 1] - w.paper.g) < 2.0 / 255;
      bare += isBare;
      below += w.height[i] < a;
      belowEdge += w.height[i] < a - edge;
      wrong += isBare && w.height[i] >= a;
    }
    SCOPED_TRACE(testing::Message() << "dry_brush " << dry);
    EXPECT_GE(bare, belowEdge);
    EXPECT_LE(bare, below);
    EXPECT_EQ(wrong, 0) << "a peak went bare";
    EXPECT_GT(bare, last);
    last = bare;
  }
  EXPECT_GT(last, 256 * 256 / 20);
}

// Granulation: pigment gathers in the valleys (negative correlation with height) and the
// wash keeps its tone on average.
TEST_F(Substrate, GranulationGathersPigmentInTheValleysAndKeepsTheTone) {
  const FlatWash w = flatWash({{"dry_brush", 0.0}, {"granulation", 2.0}, {"lighting", 0.0}, {"distortion", 0.0}});
  std::vector<double> pigment;
  double mean = 0.0;
  for (int i = 0; i < 256 * 256; ++i) {
    const double t = w.out.pixels[3 * i + 1] / w.paper.g;
    pigment.push_back(1.0 - t);
    mean += t;
  }
  mean /= 256 * 256;
  EXPECT_LT(correlation(pigment, w.height), -0.9);
  EXPECT_NEAR(mean, 0.6, 0.03);
  const auto [lo, hi] = std::minmax_element(pigment.begin(), pigment.end());
  EXPECT_GT(*hi - *lo, 0.1) << "the effect is visible";
}

// Each effect is weighted per object: a weight of 0 draws the object as if the effect were off
// (distortion moves nothing on an even wash, so it is not among them).
TEST_F(Substrate, AnObjectsWeightOfZeroTurnsItsEffectOff) {
  const json none = {{"dry_brush", 0.0}, {"granulation", 0.0}, {"lighting", 0.0}, {"distortion", 0.0}};
  const FlatWash off = flatWash(none);
  for (const char* effect : {"dry_brush", "granulation", "lighting"}) {
    SCOPED_TRACE(effect);
    json on = none;
    on[effect] = 0.8;
    const FlatWash full = flatWash(on), weighted = flatWash(on, {-0.5, 0.3, 0.8}, {{effect, 0.0}});
    EXPECT_NE(full.out.pixels, off.out.pixels) << "the effect shows at weight 1";
    EXPECT_EQ(weighted.out.pixels, off.out.pixels);
  }
}

// A scanned paper (substrate.texture): its grey is the height, tiled a texel a pixel. Stripes
// four pixels wide, black then white: dry brush bares the black (low) columns only.
TEST_F(Substrate, AScannedPaperGivesTheHeight) {
  const test::TempDir dir;
  image::Image stripes(8, 8, 1);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) stripes.at(x, y, 0) = x < 4 ? 0.2f : 0.9f;
  image::saveImage(stripes, dir / "paper.png");
  const FlatWash w = flatWash({{"texture", (dir / "paper.png").string()},
                               {"dry_brush", 0.6},
                               {"dry_edge", 0.02},
                               {"granulation", 0.0},
                               {"lighting", 0.0},
                               {"distortion", 0.0}});
  int bareLow = 0, bareHigh = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const bool bare = std::abs(w.out.at(x, y, 1) - w.paper.g) < 2.0 / 255;
      (x % 8 < 4 ? bareLow : bareHigh) += bare;
    }
  EXPECT_EQ(bareLow, 128 * 256);
  EXPECT_EQ(bareHigh, 0);
  test::expectErrorNaming([&] { flatWash({{"texture", (dir / "missing.png").string()}}); }, "missing.png", "");
}

// Substrate lighting: the relief shows, the sheet keeps its brightness, and light from the
// mirrored side shades it the other way.
TEST_F(Substrate, LightingRakesTheReliefFromTheLightsSide) {
  const json only = {{"dry_brush", 0.0}, {"granulation", 0.0}, {"lighting", 0.6}, {"distortion", 0.0}};
  const FlatWash left = flatWash(only, {-1.0, 0.0, 0.6}), right = flatWash(only, {1.0, 0.0, 0.6});
  std::vector<double> a, b;
  double mean = 0.0;
  for (int i = 0; i < 256 * 256; ++i) {
    a.push_back(left.out.pixels[3 * i + 1]);
    b.push_back(right.out.pixels[3 * i + 1]);
    mean += a.back();
  }
  mean /= 256 * 256;
  EXPECT_NEAR(mean / (0.6 * left.paper.g), 1.0, 0.03);
  EXPECT_LT(correlation(a, b), -0.5);
  const auto [lo, hi] = std::minmax_element(a.begin(), a.end());
  EXPECT_GT(*hi - *lo, 0.05);
}

// Edge darkening (seed 003) on a grey square seen from above on paper: the wash darkens
// within the blur's reach of its border and nowhere else; the paper stays as it was. With
// wobble, the straight border wanders, by at most the wobble.
struct Square {
  image::Image with, without;
  int lo = 0, hi = 0;  // the square's first and last pixel column (and row) without wobble
};

Square edgedSquare(const json& edges) {
  const json object = {
      {"lines", {{"enabled", false}, {"bg_color", {0.6, 0.6, 0.6}}}}, {"shading", {{"enabled", false}}}, {"up", "z"}};
  json top = {{"output", {{"fade", 0.0}}}, {"edges", edges}};
  top["edges"]["enabled"] = true;
  const scene::Scene s = sceneWith(object, top), s0 = sceneWith(object, {{"output", {{"fade", 0.0}}}});
  const mesh::Mesh square = mesh::heightGrid(33, 33, 1.0 / 32, [](double, double) { return 0.0; });
  InkRenderer r(s, prepare(s, square)), r0(s0, prepare(s0, square));
  EXPECT_TRUE(contains(r.passesBuilt(), "edges"));
  EXPECT_FALSE(contains(r0.passesBuilt(), "edges"));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {0, 90, 0.6});
  Square q;
  q.with = r.render(cam, 256, 256).colour(0).download(3);
  q.without = r0.render(cam, 256, 256).colour(0).download(3);
  const image::Image world = r0.worldPositions();
  q.lo = 256;
  for (int x = 0; x < 256; ++x)
    if (world.at(x, 128, 3) > 0.5) q.lo = std::min(q.lo, x), q.hi = std::max(q.hi, x);
  return q;
}

TEST_F(Substrate, EdgeDarkeningDarkensAWashWithinReachOfItsBorderOnly) {
  const double radius = 16.0 * 256 / 1024.0;  // px at this size
  const Square q = edgedSquare({{"strength", 1.0}, {"radius", 16.0}, {"samples", 5}, {"wobble", 0.0}});
  ASSERT_GT(q.hi - q.lo, 100);
  int rim = 0, rimDarker = 0, changedFar = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) {
      const double d = q.without.at(x, y, 1) - q.with.at(x, y, 1);
      const int in = std::min({x - q.lo, q.hi - x, y - q.lo, q.hi - y});  // distance inside, px
      if (in >= 1 && in <= radius - 1.0) {
        ++rim;
        rimDarker += d > 0.02;
      } else if (in > radius + 3.0 || in < -radius - 3.0) {
        changedFar += std::abs(d) > 1.5 / 255;
      }
    }
  EXPECT_GT(rim, 300);
  EXPECT_GE(rimDarker, rim * 95 / 100);
  EXPECT_EQ(changedFar, 0);
}

TEST_F(Substrate, WobblyEdgesWanderByAtMostTheWobble) {
  const double wobble = 8.0 * 256 / 1024.0;
  const Square q = edgedSquare({{"strength", 0.0}, {"wobble", 8.0}, {"wobble_scale", 24.0}});
  // Per row, where the left border now is.
  std::vector<double> border;
  for (int y = q.lo + 8; y <= q.hi - 8; ++y) {
    int x = 0;
    while (x < 128 && std::abs(q.with.at(x, y, 1) - q.without.at(128, 128, 1)) > 0.05) ++x;
    border.push_back(x);
  }
  double mean = 0, var = 0, worst = 0;
  for (double b : border) mean += b;
  mean /= border.size();
  for (double b : border) {
    var += (b - mean) * (b - mean);
    worst = std::max(worst, std::abs(b - q.lo));
  }
  EXPECT_GT(std::sqrt(var / border.size()), 0.3) << "the border wanders";
  EXPECT_LE(worst, wobble + 1.0);
}

}  // namespace
}  // namespace shanshui::render
