// A painting's composition (issue 45): texture marks denser in shadow than on lit slopes
// and absent from flat ground, several ranges each lighter with distance, the land framed
// by what is drawn of it, open water between ranges, objects standing on their ground, and
// none of it built for a scene that does not use it.
#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "gl_test.h"
#include "shanshui/render/camera.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene_assets.h"
#include "test_meshes.h"

namespace shanshui::render {
namespace {

using nlohmann::json;

class Composition : public test::HeadlessGl {};

constexpr int kWidth = 256, kHeight = 192;

// A ridge along x: z = 60 − 0.6 (|y − 100| − 10) over x, y in [0, 200], a flat top 20 wide.
mesh::Mesh ridge() {
  return test::heightGrid(81, 81, 2.5,
                          [](double, double y) { return 60.0 - 0.6 * std::max(std::abs(y - 100.0) - 10.0, 0.0); });
}

json plainObject(const json& extra = json::object()) {
  json o = {{"mesh", "memory.obj"},
            {"up", "z"},
            {"recentre", false},
            {"lines", {{"enabled", false}}},
            {"border", {{"mode", "keep"}}},
            {"shading", {{"enabled", false}}}};
  o.update(extra, true);
  return o;
}

scene::Scene sceneOf(const json& objects, const json& top = json::object()) {
  json j = {{"objects", objects}, {"output", {{"fade", 0.0}, {"width", kWidth}, {"height", kHeight}}}};
  j.update(top, true);
  return scene::parseScene(j, "test", ".");
}

std::vector<scene::LoadedObject> load(const scene::Scene& s, const std::vector<mesh::Mesh>& meshes) {
  std::vector<scene::LoadedObject> out;
  for (std::size_t i = 0; i < meshes.size(); ++i)
    out.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(meshes[i], s.objects[i])), nullptr});
  return out;
}

// Ink of a pixel: how far its red channel is below the paper's.
double inkAt(const image::Image& c, int x, int y, const scene::Scene& s) {
  return std::max(0.0, s.output.paper.x - c.at(x, y, 0));
}

TEST_F(Composition, MarksAreDenserInShadowThanOnLitSlopesAndAbsentOnFlatGround) {
  // Light from +y: the slope facing +y (y > 110) is lit, the one facing −y in shadow.
  const scene::Scene s = sceneOf(
      json::array({plainObject({{"marks", {{"style", "hemp"}, {"density", 0.6}, {"lit", 0.2}, {"ridge", 0.0}}}})}),
      {{"light", {{"direction", {0.0, 1.0, 0.6}}}}});
  InkRenderer r(s, load(s, {ridge()}));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), static_cast<double>(kWidth) / kHeight, {0, 70, 1.3});
  const image::Image c = r.render(cam, kWidth, kHeight).colour(0).download(3);
  const image::Image pos = r.worldPositions();
  double shadow = 0, lit = 0, flat = 0;
  int n_shadow = 0, n_lit = 0, n_flat = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      const double wx = pos.at(x, y, 1);
      const double ink = inkAt(c, x, y, s) > 0.1 ? 1.0 : 0.0;
      if (wx < 85.0) {
        shadow += ink, ++n_shadow;
      } else if (wx > 115.0) {
        lit += ink, ++n_lit;
      } else if (std::abs(wx - 100.0) < 8.0) {
        flat += ink, ++n_flat;
      }
    }
  }
  ASSERT_GT(n_shadow, 2000);
  ASSERT_GT(n_lit, 2000);
  ASSERT_GT(n_flat, 300);
  const double d_shadow = shadow / n_shadow, d_lit = lit / n_lit;
  EXPECT_GT(d_shadow, 0.01) << "marks are drawn in shadow";
  EXPECT_GT(d_shadow, 2.0 * d_lit) << "shadow " << d_shadow << ", lit " << d_lit;
  EXPECT_EQ(flat, 0.0) << "flat ground stays bare";
}

// Ink on the slope facing the camera (world y below 85) of the ridge seen from −y, with the
// light from `light`: the share of its pixels with ink, and the mean lengths of the inked
// runs along the picture's rows and columns.
struct SlopeInk {
  double share = 0.0, run_x = 0.0, run_y = 0.0;
  int pixels = 0, flat_inked = 0;
};

SlopeInk wetStrokesOnTheNearSlope(const json& marks, const glm::dvec3& light, double azimuth = -90.0) {
  const scene::Scene s = sceneOf(json::array({plainObject({{"marks", marks}})}),
                                 {{"light", {{"direction", {light.x, light.y, light.z}}}},
                                  {"camera", {{"azimuth", azimuth}, {"elevation", 35.0}}}});
  InkRenderer r(s, load(s, {ridge()}));
  const OrbitCamera cam = r.camera({azimuth, 35, 1.3}, static_cast<double>(kWidth) / kHeight);
  const image::Image c = r.render(cam, kWidth, kHeight).colour(0).download(3);
  const image::Image pos = r.worldPositions();
  std::vector<char> inked(static_cast<std::size_t>(kWidth) * kHeight, 0);
  SlopeInk out;
  int inked_pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      const bool ink = inkAt(c, x, y, s) > 0.1;
      const double wy = pos.at(x, y, 1);
      if (std::abs(wy - 100.0) < 8.0) out.flat_inked += ink;
      if (wy >= 85.0) continue;
      ++out.pixels;
      inked_pixels += ink;
      inked[static_cast<std::size_t>(y) * kWidth + x] = ink;
    }
  out.share = out.pixels > 0 ? static_cast<double>(inked_pixels) / out.pixels : 0.0;
  // Mean run length of inked pixels along rows, then along columns.
  auto meanRun = [&](bool rows) {
    int runs = 0, total = 0;
    const int outer = rows ? kHeight : kWidth, inner = rows ? kWidth : kHeight;
    for (int a = 0; a < outer; ++a) {
      int run = 0;
      for (int b = 0; b <= inner; ++b) {
        const bool on =
            b < inner &&
            inked[rows ? static_cast<std::size_t>(a) * kWidth + b : static_cast<std::size_t>(b) * kWidth + a];
        if (on) {
          ++run;
        } else if (run > 0) {
          ++runs, total += run, run = 0;
        }
      }
    }
    return runs > 0 ? static_cast<double>(total) / runs : 0.0;
  };
  out.run_x = meanRun(true);
  out.run_y = meanRun(false);
  return out;
}

TEST_F(Composition, WetStrokesDarkenTheShadowedSlopeRunningDownThePictureAndLeaveFlatGroundBare) {
  const json marks = {{"style", "none"}, {"wash", 1.0}, {"wash_size", 120}, {"wash_ink", 0.8}, {"wash_lit", 0.1}};
  // The slope facing the camera (−y) in shadow (light from +y), then lit (light from −y).
  const SlopeInk shadow = wetStrokesOnTheNearSlope(marks, {0.0, 1.0, 0.6});
  const SlopeInk lit = wetStrokesOnTheNearSlope(marks, {0.0, -1.0, 0.6});
  ASSERT_GT(shadow.pixels, 3000);
  EXPECT_GT(shadow.share, 0.08) << "wet strokes on the shadowed slope: " << shadow.share;
  EXPECT_GT(shadow.share, 3.0 * lit.share) << "shadow " << shadow.share << ", lit " << lit.share;
  // Laid on the picture plane down the fall line: on a slope facing the viewer they run
  // down the picture, so an inked run is longer down a column than along a row.
  EXPECT_GT(shadow.run_y, 1.8 * shadow.run_x) << "down " << shadow.run_y << ", across " << shadow.run_x;
  EXPECT_EQ(shadow.flat_inked, 0) << "the flat top stays bare";
  // The fine marks alone (no wash) leave the slope far lighter: the strokes are the wash's.
  const SlopeInk none = wetStrokesOnTheNearSlope({{"style", "hemp"}, {"density", 0.0}}, {0.0, 1.0, 0.6});
  EXPECT_LT(none.share, 0.01);
}

TEST_F(Composition, WetStrokesFollowTheFallLineOrRunStraightDownThePicture) {
  // Seen from 50 degrees off the slope's facing, its fall line runs across the picture
  // diagonally: followed (wash_follow 1) the strokes lean with it, otherwise (0) they run
  // down the columns.
  json marks = {{"style", "none"}, {"wash", 1.0}, {"wash_size", 120}, {"wash_ink", 0.8}, {"wash_lit", 1.0}};
  marks["wash_follow"] = 1.0;
  const SlopeInk follow = wetStrokesOnTheNearSlope(marks, {0.0, 1.0, 0.6}, -40.0);
  marks["wash_follow"] = 0.0;
  const SlopeInk straight = wetStrokesOnTheNearSlope(marks, {0.0, 1.0, 0.6}, -40.0);
  ASSERT_GT(follow.share, 0.05);
  ASSERT_GT(straight.share, 0.05);
  EXPECT_GT(straight.run_y / straight.run_x, 1.3 * follow.run_y / follow.run_x)
      << "straight " << straight.run_y << "/" << straight.run_x << ", following " << follow.run_y << "/"
      << follow.run_x;
}

TEST_F(Composition, BroadWetStrokesCoverMoreOfTheSlopeInWiderBundlesStillRunningDownIt) {
  json marks = {{"style", "none"}, {"wash", 1.0}, {"wash_size", 120}, {"wash_ink", 0.8}, {"wash_lit", 0.1}};
  marks["wash_width"] = 1.0;
  const SlopeInk thin = wetStrokesOnTheNearSlope(marks, {0.0, 1.0, 0.6});
  marks["wash_width"] = 2.0;
  const SlopeInk broad = wetStrokesOnTheNearSlope(marks, {0.0, 1.0, 0.6});
  ASSERT_GT(thin.share, 0.05);
  EXPECT_GT(broad.share, 1.4 * thin.share) << "broad " << broad.share << ", thin " << thin.share;
  // A broad group's strokes lie side by side, closer than their width, so an inked run along
  // a row crosses several of them.
  EXPECT_GT(broad.run_x, 1.3 * thin.run_x) << "across: broad " << broad.run_x << ", thin " << thin.run_x;
  // Still strokes down the slope, not a flat tone.
  EXPECT_GT(broad.run_y, 1.3 * broad.run_x) << "down " << broad.run_y << ", across " << broad.run_x;
}

TEST_F(Composition, FarRangesCarryLessInkThanNearOnes) {
  // Three copies of the ridge, 0, 600 and 1500 units away along +y, the camera to the south;
  // the mist lies between them and spares the nearest.
  json objects = json::array();
  for (const auto& [y, z] : {std::pair{0.0, 0.0}, {600.0, 40.0}, {1500.0, 110.0}})
    objects.push_back(plainObject({{"transform", {{"translate", {0.0, y, z}}}},
                                   {"lines", {{"enabled", true}, {"width", 2.5}}},
                                   {"shading", {{"enabled", true}}}}));
  const scene::Scene s = sceneOf(
      objects,
      {{"output", {{"fade", 0.6}}}, {"mist", {{"density", 0.7}, {"height", 0.3}, {"softness", 0.4}, {"near", 0.0}}}});
  InkRenderer r(s, load(s, {ridge(), ridge(), ridge()}));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), static_cast<double>(kWidth) / kHeight, {-90, 12, 1.0});
  const image::Image c = r.render(cam, kWidth, kHeight).colour(0).download(3);
  const image::Image pos = r.worldPositions();
  std::array<double, 3> ink{}, count{};
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      const double wy = pos.at(x, y, 1);
      const int range = wy < 300.0 ? 0 : wy < 1000.0 ? 1 : 2;
      ink[range] += inkAt(c, x, y, s);
      count[range] += 1;
    }
  }
  for (int k = 0; k < 3; ++k) ASSERT_GT(count[k], 100) << "range " << k << " is seen";
  const double near = ink[0] / count[0], middle = ink[1] / count[1], far = ink[2] / count[2];
  EXPECT_GT(near, 1.3 * middle) << near << " " << middle;
  EXPECT_GT(middle, 1.3 * far) << middle << " " << far;
}

TEST_F(Composition, TheHighDistanceOfSeveralRangesSeesTheFarPeakOverTheNearOnes) {
  // A far ridge twice as high behind two near ones: standing at the foot of the land, the
  // near ridges would hide it; the preset rises over them and the far ridge fills the top
  // of the frame.
  json objects = json::array();
  for (const auto& [y, z] : {std::pair{0.0, 0.0}, {500.0, 20.0}, {1400.0, 0.0}}) {
    json o = plainObject({{"transform", {{"translate", {0.0, y, z}}, {"scale", {1.0, 1.0, y > 1000.0 ? 3.0 : 1.0}}}},
                          {"shading", {{"enabled", true}}}});
    o.erase("mesh");
    o["dem"] = "memory.asc";  // a terrain, as compositions are made of (the mesh is given below)
    objects.push_back(o);
  }
  const scene::Scene s = sceneOf(objects, {{"camera", {{"preset", "high"}, {"azimuth", -90.0}}}});
  ASSERT_TRUE(s.isComposition());
  InkRenderer r(s, load(s, {ridge(), ridge(), ridge()}));
  r.render(r.camera({-90, 0, 1.0}, static_cast<double>(kWidth) / kHeight), kWidth, kHeight);
  const image::Image pos = r.worldPositions();
  int far = 0, land = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (pos.at(x, y, 3) > 0.5f) ++land, far += pos.at(x, y, 1) > 1000.0f;
  ASSERT_GT(land, 1000);
  EXPECT_GT(far, kWidth * kHeight / 10) << "the far ridge is seen over the near ones (" << far << " of " << land << ")";
}

TEST(DrawnFraming, ThePointsFillTheFrameOnTwoSidesAndAreCentredOnTheOthers) {
  // An uneven cloud (a near bank, a far peak): its picture from the camera fillPoints makes
  // reaches 94 % of the frame on two opposite sides and is centred between the other two.
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 400; ++i) {
    const double a = i * 2.399963, r = std::sqrt(i / 400.0);
    points.push_back({300.0 * r * std::cos(a), 200.0 * r * std::sin(a), 20.0 * std::sin(3.0 * a)});
  }
  points.push_back({-100.0, 2500.0, 700.0});  // the far peak's top
  for (const auto& [azimuth, elevation, aspect] :
       {std::tuple{-90.0, 12.0, 0.75}, {-60.0, 30.0, 1.5}, {20.0, 45.0, 1.0}}) {
    const OrbitCamera cam = fillPoints(points, azimuth, elevation, 30.0, aspect, 1.0);
    const glm::dmat4 vp = glm::dmat4(cam.projection(aspect)) * glm::dmat4(cam.view());
    glm::dvec2 lo(1e9), hi(-1e9);
    for (const glm::dvec3& p : points) {
      const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
      ASSERT_GT(c.w, 0.0);
      lo = glm::min(lo, glm::dvec2(c) / c.w);
      hi = glm::max(hi, glm::dvec2(c) / c.w);
    }
    const int full = std::abs(hi.x - 0.94) < 1e-3 && std::abs(lo.x + 0.94) < 1e-3 ? 0 : 1;
    EXPECT_NEAR(hi[full], 0.94, 1e-3) << azimuth;
    EXPECT_NEAR(lo[full], -0.94, 1e-3) << azimuth;
    EXPECT_NEAR(hi[1 - full] + lo[1 - full], 0.0, 1e-3) << azimuth;
    EXPECT_LE(hi[1 - full], 0.94 + 1e-3) << azimuth;
  }
}

TEST_F(Composition, OpenWaterBetweenRangesCarriesWaves) {
  // Two ridges with water between them: the background where the view meets the water
  // inside the land's rectangle has wave strokes; above the horizon, none.
  json objects = json::array();
  for (double y : {0.0, 700.0}) objects.push_back(plainObject({{"transform", {{"translate", {0.0, y, 0.0}}}}}));
  auto ink = [&](bool water) {
    const scene::Scene s = sceneOf(
        objects, {{"water", {{"enabled", water}, {"level", 0.2}, {"waves", 1.0}, {"spacing", 0.03}, {"ink", 1.0}}},
                  {"canvas", {{"type", "none"}}}});
    InkRenderer r(s, load(s, {ridge(), ridge()}));
    const image::Image c = r.render(r.camera({-90, 30, 1.0}, static_cast<double>(kWidth) / kHeight), kWidth, kHeight)
                               .colour(0)
                               .download(3);
    const image::Image pos = r.worldPositions();
    double sum = 0.0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x)
        if (pos.at(x, y, 3) < 0.5f && inkAt(c, x, y, s) > 0.1) sum += 1.0;
    return sum;
  };
  EXPECT_EQ(ink(false), 0.0) << "bare paper without water";
  EXPECT_GT(ink(true), 50.0) << "pixels of waves on the open water";
}

TEST_F(Composition, ASceneWithoutMarksOrGroundedObjectsBuildsNothingForThem) {
  const scene::Scene plain = sceneOf(json::array({plainObject({{"shading", {{"enabled", true}}}})}));
  InkRenderer a(plain, load(plain, {ridge()}));
  for (const std::string& v : a.variants().at("ink")) EXPECT_EQ(v.find("MARKS"), std::string::npos) << v;
  EXPECT_FALSE(scene::usesGrounding(plain));
  const scene::Scene marked =
      sceneOf(json::array({plainObject({{"shading", {{"enabled", true}}}, {"marks", {{"style", "axe"}}}})}));
  InkRenderer b(marked, load(marked, {ridge()}));
  EXPECT_NE(b.variants().at("ink").front().find("MARKS"), std::string::npos);
  // Wet strokes alone build the marks' code too.
  const scene::Scene washed = sceneOf(
      json::array({plainObject({{"shading", {{"enabled", true}}}, {"marks", {{"style", "none"}, {"wash", 0.5}}}})}));
  InkRenderer w(washed, load(washed, {ridge()}));
  EXPECT_NE(w.variants().at("ink").front().find("MARKS"), std::string::npos);
  EXPECT_NE(w.variants().at("ink").front().find("WASH"), std::string::npos);
  // Marks without wet strokes build no wet strokes' code.
  for (const std::string& v : b.variants().at("ink")) EXPECT_EQ(v.find("WASH"), std::string::npos) << v;
}

TEST_F(Composition, AGroundedHutIsDrawnStandingWhereItWasPlaced) {
  json hut = plainObject({{"name", "hut"},
                          {"shading", {{"enabled", true}, {"tones", {0.1, 0.1, 0.1, 0.1, 0.1}}}},
                          {"transform", {{"translate", {100.0, 150.0, 0.0}}, {"scale", {12.0, 12.0, 12.0}}}},
                          {"ground", {{"on", "land"}}}});
  json land = plainObject({{"name", "land"}, {"shading", {{"enabled", true}}}});
  const scene::Scene s = sceneOf(json::array({land, hut}));
  std::vector<mesh::Mesh> meshes{ridge(), mesh::unitCube()};
  InkRenderer r(s, load(s, meshes));
  // The cube's base at the lowest ground under its footprint (the slope falls along +y).
  const glm::dvec3 base(r.worldMatrix(1) * glm::dvec4(0.5, 0.5, 0.0, 1.0));
  const double ground = 60.0 - 0.6 * (156.0 - 100.0 - 10.0);
  EXPECT_NEAR(base.z, ground - 0.05 * 12.0, 1e-6);
  EXPECT_NEAR(base.y, 150.0, 1e-6);
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), static_cast<double>(kWidth) / kHeight, {60, 35, 1.0});
  r.render(cam, kWidth, kHeight);
  // Pixels showing the hut: inside its footprint, above the ground there.
  const image::Image pos = r.worldPositions();
  int hut_pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (pos.at(x, y, 3) > 0.5f && std::abs(pos.at(x, y, 0) - 100.0) < 6.5 &&
          std::abs(pos.at(x, y, 1) - 150.0) < 6.5 && pos.at(x, y, 2) > 60.0 - 0.6 * (144.0 - 110.0) + 0.5)
        ++hut_pixels;
  EXPECT_GT(hut_pixels, 20) << "the hut is drawn where it stands";
}

}  // namespace
}  // namespace shanshui::render
