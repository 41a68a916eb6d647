// The elements pass (issue 44) against what is known of each element: a dot stays on its
// surface point through an orbit, a ridge hides what stands behind it, a tree's ink changes
// continuously as it recedes, the same seed paints the same picture, and a scene without
// elements builds nothing for them.
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl_test.h"
#include "scene_in_memory.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::render {
namespace {

using nlohmann::json;

class Elements : public test::HeadlessGl {};

constexpr int kWidth = 320, kHeight = 240;

// A one-object scene on `m` (model = world: z up, not recentred) that draws elements and
// nothing else of the surface: no lines, no shading, no atmosphere.
scene::Scene elementScene(json extra = json::object()) {
  json o = {{"up", "z"},
            {"recentre", false},
            {"lines", {{"enabled", false}}},
            {"shading", {{"enabled", false}}},
            {"border", {{"mode", "keep"}}},
            {"dots", {{"enabled", true}, {"size", 24.0}}}};
  o.update(extra, true);
  return test::sceneWith(o, {{"output", {{"fade", 0.0}, {"width", kWidth}, {"height", kHeight}}}});
}

std::vector<scene::LoadedObject> withElements(const scene::Scene& s, const mesh::Mesh& m,
                                              std::vector<elements::Instance> placed) {
  std::vector<scene::LoadedObject> loaded = test::prepare(s, m);
  auto set = std::make_shared<scene::ElementSet>();
  set->instances = std::move(placed);
  loaded[0].elements = std::move(set);
  return loaded;
}

elements::Instance dotAt(glm::vec3 p) {
  elements::Instance i;
  i.position = p;
  i.kind = elements::Kind::MossDot;
  i.size = 1.0f;
  i.seed = 12345;
  return i;
}

// Where world point p lands in a picture (x right, y down from the top row; pixel centres at
// half integers).
glm::dvec2 projected(const OrbitCamera& cam, glm::dvec3 p) {
  const glm::dvec4 c =
      glm::dmat4(cam.projection(static_cast<double>(kWidth) / kHeight)) * glm::dmat4(cam.view()) * glm::dvec4(p, 1.0);
  return {(c.x / c.w + 1.0) * 0.5 * kWidth, (1.0 - c.y / c.w) * 0.5 * kHeight};
}

// The elements' ink (row 0 at the top).
image::Image elementInk(const InkRenderer& r) {
  return r.passTarget("elements")->colour(0).download(2);
}

// The ink-weighted centre of the ink within `radius` pixels of `around`, and its total.
glm::dvec3 inkCentre(const image::Image& ink, glm::dvec2 around, double radius) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < ink.height; ++y) {
    for (int x = 0; x < ink.width; ++x) {
      const glm::dvec2 p(x + 0.5, y + 0.5);
      if (glm::length(p - around) > radius) continue;
      const double v = ink.at(x, y, 0);
      sum += glm::dvec3(v * p, v);
    }
  }
  return sum.z > 0.0 ? glm::dvec3(glm::dvec2(sum) / sum.z, sum.z) : glm::dvec3(0.0);
}

// GLSL's smoothstep, as the oracles below take it.
double smoothStep(double lo, double hi, double x) {
  const double u = std::clamp((x - lo) / (hi - lo), 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}

// The share of its ink an element keeps where the border leaves `ground` of the land:
// full from half the ground up, none below a twentieth (elements_expand.comp's borderInk).
double elementBorderInk(double ground) {
  return smoothStep(0.05, 0.5, ground);
}

// The elements' total ink in the view both border tests take, for one element on mesh m.
double elementInkSum(const scene::Scene& s, const mesh::Mesh& m, const elements::Instance& e) {
  InkRenderer r(s, withElements(s, m, {e}));
  r.render(r.camera({-60.0, 15.0, 1.0}, static_cast<double>(kWidth) / kHeight), kWidth, kHeight);
  double sum = 0.0;
  for (float v : elementInk(r).pixels) sum += v;
  return sum;
}

mesh::Mesh plane() {
  return mesh::heightGrid(
      21, 21, 10.0, [](double, double) { return 0.0; }, glm::dvec3(-100.0, -100.0, 0.0));
}

TEST_F(Elements, ASceneWithoutElementsBuildsNothingForThem) {
  const mesh::Mesh m = plane();
  const scene::Scene bare = elementScene({{"dots", {{"enabled", false}}}});
  InkRenderer without(bare, test::prepare(bare, m));
  EXPECT_EQ(std::count(without.passesBuilt().begin(), without.passesBuilt().end(), "elements"), 0);
  for (const std::string& v : without.variants().at("ink")) EXPECT_EQ(v.find("ELEMENTS"), std::string::npos) << v;
  // Trees asked for but at no density: nothing either.
  const scene::Scene none =
      elementScene({{"dots", {{"enabled", false}}}, {"trees", {{"enabled", true}, {"density", 0.0}}}});
  InkRenderer also(none, test::prepare(none, m));
  EXPECT_EQ(std::count(also.passesBuilt().begin(), also.passesBuilt().end(), "elements"), 0);
  const scene::Scene s = elementScene();
  InkRenderer with(s, withElements(s, m, {dotAt({0, 0, 0})}));
  EXPECT_EQ(std::count(with.passesBuilt().begin(), with.passesBuilt().end(), "elements"), 1);
  EXPECT_NE(with.variants().at("ink").front().find("ELEMENTS"), std::string::npos);
}

// A frame has room for a bounded number of marks; what does not fit is left out and counted,
// not lost silently. Forty moss dots in view (one mark each) with room for 25: 15 dropped;
// with the room a scene gets by default, none.
TEST_F(Elements, MarksWithoutRoomInTheFrameAreCounted) {
  const mesh::Mesh m = plane();
  const scene::Scene s = elementScene();
  std::vector<elements::Instance> dots;
  for (int i = 0; i < 40; ++i)
    dots.push_back(dotAt(glm::vec3(-45.0f + 10.0f * (i % 10), -30.0f + 20.0f * (i / 10), 0.0f)));
  auto drawn = [&](const char* room, std::size_t& dropped) {
    if (room) setenv("SHANSHUI_ELEMENT_MARKS", room, 1);
    InkRenderer r(s, withElements(s, m, dots));
    unsetenv("SHANSHUI_ELEMENT_MARKS");
    r.render(r.camera({-60.0, 40.0, 1.0}, static_cast<double>(kWidth) / kHeight), kWidth, kHeight);
    dropped = r.marksDropped();
    double sum = 0.0;
    for (float v : elementInk(r).pixels) sum += v;
    return sum;
  };
  std::size_t all_dropped = 1, some_dropped = 0;
  const double all = drawn(nullptr, all_dropped), some = drawn("25", some_dropped);
  EXPECT_EQ(all_dropped, 0u);
  EXPECT_EQ(some_dropped, 15u) << "forty dots made, room for 25";
  EXPECT_NEAR(some / all, 25.0 / 40.0, 0.1) << "the ink of 25 dots of the 40";
}

TEST_F(Elements, ADotStaysOnItsSurfacePointThroughAnOrbit) {
  const mesh::Mesh m = plane();
  const scene::Scene s = elementScene();
  const std::vector<glm::vec3> points{{0, 0, 0}, {40, -30, 0}, {-55, 35, 0}};
  std::vector<elements::Instance> dots;
  for (const glm::vec3& p : points) dots.push_back(dotAt(p));
  InkRenderer r(s, withElements(s, m, dots));
  double worst = 0.0;
  for (double azimuth = -180.0; azimuth < 180.0; azimuth += 30.0) {
    for (double elevation : {20.0, 50.0}) {
      const OrbitCamera cam = r.camera({azimuth, elevation, 1.0}, static_cast<double>(kWidth) / kHeight);
      r.render(cam, kWidth, kHeight);
      const image::Image ink = elementInk(r);
      for (const glm::vec3& p : points) {
        const glm::dvec2 at = projected(cam, glm::dvec3(p));
        const glm::dvec3 c = inkCentre(ink, at, 8.0);
        ASSERT_GT(c.z, 5.0) << "no dot near " << at.x << ", " << at.y << " at azimuth " << azimuth;
        worst = std::max(worst, glm::length(glm::dvec2(c) - at));
      }
    }
  }
  EXPECT_LT(worst, 0.5) << "pixels between a dot's ink and its surface point";
}

TEST_F(Elements, ARidgeHidesWhatStandsBehindIt) {
  // A ridge 40 high along y at x = 0; one dot at its foot on the far side, one on the near.
  const mesh::Mesh m = mesh::heightGrid(
      81, 21, 5.0, [](double x, double) { return 40.0 * std::exp(-std::pow((x - 200.0) / 25.0, 2)); },
      glm::dvec3(-200.0, -50.0, 0.0));
  const scene::Scene s = elementScene();
  const glm::vec3 behind(120.0f, 0.0f, 0.0f), before(-120.0f, 0.0f, 0.0f);
  InkRenderer r(s, withElements(s, m, {dotAt(behind), dotAt(before)}));
  // Looking along +x from low down: the ridge stands between the eye and `behind`.
  const OrbitCamera cam = r.camera({180.0, 8.0, 1.0}, static_cast<double>(kWidth) / kHeight);
  r.render(cam, kWidth, kHeight);
  const image::Image ink = elementInk(r);
  const glm::dvec2 a = projected(cam, glm::dvec3(behind)), b = projected(cam, glm::dvec3(before));
  ASSERT_TRUE(a.x > 0 && a.x < kWidth && a.y > 0 && a.y < kHeight) << a.x << " " << a.y;
  // Is the far dot really behind the ridge from here? The ridge's crest projects above it.
  EXPECT_LT(projected(cam, {0.0, 0.0, 40.0}).y, a.y);
  EXPECT_EQ(inkCentre(ink, a, 4.0).z, 0.0);
  EXPECT_GT(inkCentre(ink, b, 4.0).z, 5.0);
  // Without the ridge the far dot shows.
  const mesh::Mesh flat = mesh::heightGrid(
      81, 21, 5.0, [](double, double) { return 0.0; }, glm::dvec3(-200.0, -50.0, 0.0));
  InkRenderer open(s, withElements(s, flat, {dotAt(behind), dotAt(before)}));
  open.render(cam, kWidth, kHeight);
  EXPECT_GT(inkCentre(elementInk(open), a, 4.0).z, 5.0);
}

TEST_F(Elements, ATreesInkChangesContinuouslyAsItRecedes) {
  const mesh::Mesh m = plane();
  for (elements::Kind kind :
       {elements::Kind::Pine, elements::Kind::Leafy, elements::Kind::Bare, elements::Kind::Distant}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const scene::Scene s = elementScene({{"dots", {{"enabled", false}}}, {"trees", {{"enabled", true}}}});
    elements::Instance tree;
    tree.kind = kind;
    tree.size = 20.0f;
    tree.seed = 3;
    InkRenderer r(s, withElements(s, m, {tree}));
    // Dolly out in steps of 4 % of the distance: the tree goes from ~150 px high to ~3 px,
    // through both cross-fades, and its ink (the sum over the picture) should scale about
    // as its area on screen, never jump.
    std::vector<double> ink;
    for (double zoom = 4.0; zoom > 0.08; zoom /= 1.04) {
      const OrbitCamera cam = r.camera({-60.0, 15.0, zoom}, static_cast<double>(kWidth) / kHeight);
      r.render(cam, kWidth, kHeight);
      const image::Image e = elementInk(r);
      double sum = 0.0;
      for (int y = 0; y < e.height; ++y)
        for (int x = 0; x < e.width; ++x) sum += e.at(x, y, 0);
      ink.push_back(sum);
    }
    ASSERT_GT(ink.front(), 50.0);
    ASSERT_GT(ink.back(), 0.05);
    // While the tree carries at least two pixels' worth of ink (below that a mark narrower
    // than a pixel covers one pixel centre or two, whatever the brushwork does).
    double largest = 0.0;
    for (std::size_t i = 1; i < ink.size() && ink[i] >= 2.0; ++i)
      largest = std::max(largest, std::abs(std::log(ink[i] / ink[i - 1])));
    // The area alone changes by 2 log 1.04 = 0.08 a step; a level dropped at once would
    // change it by a factor of two or more.
    EXPECT_LT(largest, 0.3);
  }
}

// The dissolving border washes the ground out over its whole band, but a tree keeps its ink
// until the ground is half gone, and fades out only at the band's outer part (a painter's
// nearest trees stay dark where the bank dissolves at its front). A tree at several depths
// into the band (roughness 0: the border is smoothstep(t), t the depth over the width)
// against the same tree with a hard edge: its ink is smoothstep(0.05, 0.5, border).
TEST_F(Elements, ATreeInADissolvingBorderKeepsItsInkUntilTheGroundIsHalfGone) {
  const mesh::Mesh m = plane();  // 200 x 200: half-extent 100, so a width of 0.3 is 30
  const double width = 30.0;
  for (double inside : {4.5, 7.5, 10.5, 12.0, 15.0, 24.0}) {
    SCOPED_TRACE(inside);
    elements::Instance tree;
    tree.kind = elements::Kind::Leafy;
    tree.position = glm::vec3(100.0 - inside, 0.0f, 0.0f);
    tree.size = 40.0f;
    tree.seed = 7;
    auto ink = [&](const char* mode) {
      return elementInkSum(elementScene({{"dots", {{"enabled", false}}},
                                         {"trees", {{"enabled", true}}},
                                         {"border", {{"mode", mode}, {"width", width / 100.0}, {"roughness", 0.0}}}}),
                           m, tree);
    };
    const double whole = ink("keep"), kept = ink("dissolve");
    ASSERT_GT(whole, 50.0) << "the tree is in view";
    const double ground = smoothStep(0.0, 1.0, inside / width);
    EXPECT_NEAR(kept / whole, elementBorderInk(ground), 0.03) << "the ground keeps " << ground;
    if (ground > 0.25) {
      EXPECT_GT(kept / whole, ground + 0.05) << "darker than the ground under it";
    }
  }
}

// A small element (a moss dot, a far tree's dab) reads the border's ragged edge itself, the
// ink pass's noise and all, so none stands on the paper beyond it: dots at several depths
// into a band of roughness 1.2, each against the same dot with a hard edge, carry
// smoothstep(0.05, 0.5, smoothstep(t − 1.2 n)) of its ink, n the border's noise where the
// ink pass reads it (libs/noise's coarse erosion noise, the texel border_noise.glsl takes).
TEST_F(Elements, AMossDotFollowsTheBordersRaggedEdge) {
  const mesh::Mesh m = plane();
  const double width = 30.0, roughness = 1.2;
  const scene::Scene probe = elementScene();
  const image::Image noise = noise::erosionNoiseCoarse(1024, probe.seed ^ 0x5A17ull);
  int differs = 0;
  for (int k = 0; k < 12; ++k) {
    const double inside = 12.0 + 12.0 * (k % 4), across = -40.0 + 40.0 * (k / 4);
    SCOPED_TRACE(inside);
    SCOPED_TRACE(across);
    const glm::dvec2 at(across, 100.0 - inside);
    auto ink = [&](const char* mode) {
      return elementInkSum(
          elementScene({{"border", {{"mode", mode}, {"width", width / 100.0}, {"roughness", roughness}}}}), m,
          dotAt(glm::vec3(at.x, at.y, 0.0)));
    };
    const double whole = ink("keep"), kept = ink("dissolve");
    ASSERT_GT(whole, 20.0) << "the dot is in view";
    const glm::dvec2 uv = at / width * 0.25;
    const int tx = static_cast<int>(std::floor(uv.x * 1024.0 - 1.5)) & 1023;
    const int ty = static_cast<int>(std::floor(uv.y * 1024.0 - 1.5)) & 1023;
    const double n = noise.at(tx, ty, 0), t = inside / width;
    const double ground = t >= 1.0 + roughness ? 1.0 : smoothStep(0.0, 1.0, t - roughness * n);
    const double expected = elementBorderInk(ground);
    const double at_mean = elementBorderInk(smoothStep(0.0, 1.0, t - 0.5 * roughness));
    EXPECT_NEAR(kept / whole, expected, 0.04) << "noise " << n;
    differs += std::abs(expected - at_mean) > 0.15 ? 1 : 0;
  }
  EXPECT_GE(differs, 3) << "the noise moves the edge at some of the dots";
}

// Two objects side by side on one mesh, each with a tree at a different model point: each
// object draws its own, where its transform puts it, and not the other's. (The expand pass
// read every object's elements from the start of the buffer: the second object drew the
// first's trees, and none of its own beyond their number, and nothing looked amiss where
// the objects shared a mesh: the painting's near bank showed the middle range's trees.)
TEST_F(Elements, EachObjectDrawsItsOwnElements) {
  const mesh::Mesh m = plane();
  json o = {{"mesh", "memory.obj"},
            {"up", "z"},
            {"recentre", false},
            {"lines", {{"enabled", false}}},
            {"shading", {{"enabled", false}}},
            {"border", {{"mode", "keep"}}},
            {"trees", {{"enabled", true}}}};
  json a = o, b = o;
  a["transform"] = {{"translate", {-120.0, 0.0, 0.0}}};
  b["transform"] = {{"translate", {120.0, 0.0, 0.0}}};
  const scene::Scene s = scene::parseScene(
      {{"objects", {a, b}}, {"output", {{"fade", 0.0}, {"width", kWidth}, {"height", kHeight}}}}, "test", ".");
  auto treeAt = [](glm::vec3 p) {
    elements::Instance t;
    t.kind = elements::Kind::Pine;
    t.position = p;
    t.size = 40.0f;
    t.seed = 5;
    auto set = std::make_shared<scene::ElementSet>();
    set->instances = {t};
    return set;
  };
  std::vector<scene::LoadedObject> loaded;
  for (std::size_t i = 0; i < 2; ++i)
    loaded.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(m, s.objects[i])), nullptr});
  loaded[0].elements = treeAt({0.0f, 0.0f, 0.0f});
  loaded[1].elements = treeAt({60.0f, 0.0f, 0.0f});
  InkRenderer r(s, loaded);
  const OrbitCamera cam = r.camera({-90.0, 20.0, 1.0}, static_cast<double>(kWidth) / kHeight);
  r.render(cam, kWidth, kHeight);
  const image::Image e = elementInk(r);
  // The ink within reach of a point half a tree above a foot (world).
  auto inkAbove = [&](glm::dvec3 foot) {
    const glm::dvec2 top = projected(cam, foot + glm::dvec3(0.0, 0.0, 40.0));
    const glm::dvec2 base = projected(cam, foot);
    return inkCentre(e, 0.5 * (top + base), 0.6 * glm::length(top - base)).z;
  };
  const double first = inkAbove({-120.0, 0.0, 0.0}), second = inkAbove({180.0, 0.0, 0.0});
  EXPECT_GT(first, 5.0) << "the first object's tree";
  EXPECT_GT(second, 5.0) << "the second object's tree";
  EXPECT_LT(inkAbove({120.0, 0.0, 0.0}), 0.02 * second) << "the first object's tree drawn on the second";
}

// A building standing on the land stands in a clearing: no tree grows within its radius and
// half the tree's height of it, nor in front of it (between it and the eye) where the tree's
// crown would cover it on the picture; a tree beside it at twice that keeps its ink, and
// without the building the same trees all draw.
TEST_F(Elements, ABuildingStandsInAClearing) {
  const mesh::Mesh land = plane();
  json base = {{"up", "z"},
               {"recentre", false},
               {"lines", {{"enabled", false}}},
               {"shading", {{"enabled", false}}},
               {"border", {{"mode", "keep"}}}};
  json ground = base, hut = base;
  ground["name"] = "land";
  ground["mesh"] = "land.obj";
  ground["trees"] = {{"enabled", true}};
  hut["name"] = "hut";
  hut["mesh"] = "hut.obj";
  hut["transform"] = {{"translate", {0.0, 0.0, 0.0}}, {"scale", {8.0, 8.0, 8.0}}};
  hut["ground"] = {{"on", "land"}};
  const json output = {{"fade", 0.0}, {"width", kWidth}, {"height", kHeight}};
  const scene::Scene with = scene::parseScene({{"objects", {ground, hut}}, {"output", output}}, "test", ".");
  const scene::Scene without = scene::parseScene({{"objects", {ground}}, {"output", output}}, "test", ".");
  // Trees 20 high: beside the hut (radius 8·√2/2 ≈ 5.7, so the clearing reaches 15.7), in
  // front of it towards the eye, and beside it at 40.
  constexpr float kTree = 20.0f;
  const OrbitCamera probe = [&] {
    InkRenderer r(without, {{std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(land, without.objects[0])),
                             nullptr}});
    return r.camera({-60.0, 25.0, 1.0}, static_cast<double>(kWidth) / kHeight);
  }();
  const glm::dvec2 ahead = glm::normalize(glm::dvec2(probe.eye()));  // from the hut (at the origin) to the eye
  const glm::dvec2 side(-ahead.y, ahead.x);
  const std::vector<glm::dvec2> feet = {10.0 * side, 30.0 * ahead, 40.0 * side};
  auto trees = [&] {
    auto set = std::make_shared<scene::ElementSet>();
    for (const glm::dvec2& f : feet) {
      elements::Instance t;
      t.kind = elements::Kind::Pine;
      t.position = glm::vec3(glm::vec2(f), 0.0f);
      t.size = kTree;
      t.seed = 5;
      set->instances.push_back(t);
    }
    return set;
  };
  auto inkOfEachTree = [&](const scene::Scene& s) {
    std::vector<scene::LoadedObject> loaded;
    loaded.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(land, s.objects[0])), nullptr});
    if (s.objects.size() > 1)
      loaded.push_back(
          {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(mesh::unitCube(), s.objects[1])), nullptr});
    loaded[0].elements = trees();
    InkRenderer r(s, loaded);
    r.render(probe, kWidth, kHeight);
    const image::Image e = elementInk(r);
    std::vector<double> ink;
    for (const glm::dvec2& f : feet) {
      const glm::dvec3 foot(f, 0.0);
      const glm::dvec2 top = projected(probe, foot + glm::dvec3(0.0, 0.0, kTree)), bottom = projected(probe, foot);
      ink.push_back(inkCentre(e, 0.5 * (top + bottom), 0.4 * glm::length(top - bottom)).z);
    }
    return ink;
  };
  const std::vector<double> open = inkOfEachTree(without), cleared = inkOfEachTree(with);
  for (std::size_t k = 0; k < feet.size(); ++k) EXPECT_GT(open[k], 5.0) << "tree " << k << " without the hut";
  EXPECT_LT(cleared[0], 0.02 * open[0]) << "the tree beside the hut";
  EXPECT_LT(cleared[1], 0.02 * open[1]) << "the tree in front of the hut";
  EXPECT_GT(cleared[2], 0.9 * open[2]) << "the tree beside it, beyond the clearing";
}

TEST_F(Elements, TheSameSeedPaintsTheSamePicture) {
  const mesh::Mesh m = mesh::heightGrid(
      41, 41, 10.0, [](double x, double y) { return 30.0 * std::sin(x / 60.0) * std::cos(y / 50.0); },
      glm::dvec3(-200.0, -200.0, 0.0));
  auto picture = [&](int seed) {
    const scene::Scene s =
        elementScene({{"trees", {{"enabled", true}, {"density", 60.0}, {"size", 15.0}, {"seed", seed}}},
                      {"dots", {{"density", 20.0}}}});
    std::vector<scene::LoadedObject> loaded = test::prepare(s, m);
    auto set = std::make_shared<scene::ElementSet>();
    set->instances = elements::placeElements(loaded[0].geometry->mesh, s.objects[0].trees, s.objects[0].dots, s.seed);
    EXPECT_GT(set->instances.size(), 20u);
    loaded[0].elements = set;
    InkRenderer r(s, loaded);
    return r.renderImage({-60.0, 35.0, 1.0});
  };
  const image::Image a = picture(4), b = picture(4), c = picture(5);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
}

TEST_F(Elements, SomethingMovingInFrontHidesTheCachedLayer) {
  // A dot on a plane, and a box that moves over it: at t = 0 the box is 150 away, at t = 1 it
  // stands on the dot. The camera stays, so the elements' layer is not drawn again (the
  // static layer is cached); the ink pass must hide the dot by the layer's nearness.
  json j = {{"output", {{"fade", 0.0}, {"width", kWidth}, {"height", kHeight}}}, {"objects", json::array()}};
  for (const char* name : {"plane", "box"})
    j["objects"].push_back({{"mesh", name},
                            {"up", "z"},
                            {"recentre", false},
                            {"border", {{"mode", "keep"}}},
                            {"lines", {{"enabled", false}}},
                            {"shading", {{"enabled", false}}}});
  j["objects"][0]["dots"] = {{"enabled", true}, {"size", 24.0}};
  j["objects"][1]["transform"] = {{"scale", {30.0, 30.0, 30.0}}, {"translate", {-165.0, -15.0, 0.0}}};
  j["objects"][1]["velocity"] = {150.0, 0.0, 0.0};
  const scene::Scene s = scene::parseScene(j, "test", ".");
  std::vector<scene::LoadedObject> loaded = withElements(s, plane(), {dotAt({0, 0, 0})});
  loaded.push_back(
      {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(mesh::unitCube(), s.objects[1])), nullptr});
  InkRenderer r(s, loaded);
  EXPECT_NE(r.variants().at("ink").front().find("ELEMENT_NEARNESS"), std::string::npos);
  const scene::CameraKey key{-60.0, 35.0, 1.0};
  const OrbitCamera cam = r.camera(key, static_cast<double>(kWidth) / kHeight);
  const glm::dvec2 at = projected(cam, {0.0, 0.0, 0.0});
  auto inkAtDot = [&](const image::Image& picture) {
    double darkest = 1.0;
    for (int y = static_cast<int>(at.y) - 1; y <= static_cast<int>(at.y) + 1; ++y)
      for (int x = static_cast<int>(at.x) - 1; x <= static_cast<int>(at.x) + 1; ++x)
        darkest = std::min(darkest, static_cast<double>(picture.at(x, y, 1)));
    return 1.0 - darkest;
  };
  EXPECT_GT(inkAtDot(r.renderImage(key, nullptr, 0.0)), 0.5) << "the dot before the box arrives";
  const image::Image covered = r.renderImage(key, nullptr, 1.0);
  EXPECT_LT(inkAtDot(covered), 0.1) << "the dot under the box";
}

}  // namespace
}  // namespace shanshui::render
