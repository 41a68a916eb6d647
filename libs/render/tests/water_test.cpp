// Water (scene key `water`): the land below the level is hidden and left as paper, wave
// strokes lie flat and horizontal on it, a bank line follows the shore, nothing grows under
// it, and a scene without water builds none of it.
#include <algorithm>
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "gl_test.h"
#include "scene_in_memory.h"
#include "shanshui/render/camera.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene_assets.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using nlohmann::json;

class Water : public test::HeadlessGl {};

constexpr int kWidth = 256, kHeight = 192;

// A plane rising along x from z = -50 to z = 50: at level 0.5 the water's edge is x = 100.
mesh::Mesh ramp() {
  return test::heightGrid(41, 41, 5.0, [](double x, double) { return 0.5 * (x - 100.0); });
}

scene::Scene waterScene(const json& water, const json& object = json::object()) {
  json o = {{"up", "z"},
            {"recentre", false},
            {"lines", {{"enabled", false}}},
            {"border", {{"mode", "keep"}}},
            {"shading", {{"erosion", 0.0}, {"noise", 0.0}}}};
  o.update(object, true);
  return test::sceneWith(o, {{"water", water}, {"output", {{"fade", 0.0}, {"width", kWidth}, {"height", kHeight}}}});
}

struct Picture {
  image::Image colour, position;
};

Picture paint(const scene::Scene& s, const mesh::Mesh& m, double azimuth = 200.0, double zoom = 1.0) {
  InkRenderer r(s, test::prepare(s, m));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), static_cast<double>(kWidth) / kHeight, {azimuth, 35, zoom});
  Picture p;
  p.colour = r.render(cam, kWidth, kHeight).colour(0).download(3);
  p.position = r.worldPositions();
  return p;
}

TEST_F(Water, TheLandBelowTheLevelIsPaperAndTheLandAboveIsUntouched) {
  const mesh::Mesh m = ramp();
  const scene::Scene dry = waterScene({{"enabled", false}});
  const scene::Scene wet = waterScene({{"enabled", true}, {"level", 0.5}, {"waves", 0.0}, {"bank", 0.0}});
  const Picture a = paint(dry, m), b = paint(wet, m);
  const glm::dvec3 paper = wet.output.paper;
  int under = 0, above = 0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (a.position.at(x, y, 3) < 0.5f) continue;
      const float z = a.position.at(x, y, 2);
      if (std::abs(z) < 0.5f) continue;  // the shore's own pixels
      for (int c = 0; c < 3; ++c) {
        if (z < 0.0f)
          ASSERT_NEAR(b.colour.at(x, y, c), paper[c], 1.0 / 255) << x << "," << y;
        else
          ASSERT_EQ(b.colour.at(x, y, c), a.colour.at(x, y, c)) << x << "," << y;
      }
      (z < 0.0f ? under : above) += 1;
    }
  }
  EXPECT_GT(under, 3000);
  EXPECT_GT(above, 3000);
}

TEST_F(Water, WavesAreHorizontalStrokesAndTheBankIsALine) {
  const mesh::Mesh m = ramp();
  const scene::Scene s =
      waterScene({{"enabled", true}, {"level", 0.5}, {"waves", 1.0}, {"ink", 1.0}, {"bank", 2.0}, {"spacing", 0.08}},
                 {{"shading", {{"enabled", false}}}});
  const Picture p = paint(s, m, 200.0, 1.8);
  const glm::dvec3 paper = s.output.paper;
  auto dark = [&](int x, int y) { return p.colour.at(x, y, 0) < paper.x - 0.25; };
  // On the water: dark runs are long across the picture and short up it.
  long runs_x = 0, runs_y = 0, marks_x = 0, marks_y = 0, bank = 0, shore = 0;
  for (int y = 1; y + 1 < kHeight; ++y) {
    for (int x = 1; x + 1 < kWidth; ++x) {
      if (p.position.at(x, y, 3) < 0.5f) continue;
      const float z = p.position.at(x, y, 2);
      if (z < -2.0f && dark(x, y)) {
        ++marks_x;
        ++marks_y;
        runs_x += !dark(x - 1, y);
        runs_y += !dark(x, y - 1);
      }
      // Land within a pixel or two of the shore (its neighbour is under water).
      if (z >= 0.0f && (p.position.at(x + 1, y, 2) < 0.0f || p.position.at(x - 1, y, 2) < 0.0f ||
                        p.position.at(x, y + 1, 2) < 0.0f || p.position.at(x, y - 1, 2) < 0.0f)) {
        ++shore;
        bank += dark(x, y);
      }
    }
  }
  ASSERT_GT(marks_x, 200) << "waves are drawn";
  const double across = static_cast<double>(marks_x) / std::max(runs_x, 1L),
               up = static_cast<double>(marks_y) / std::max(runs_y, 1L);
  EXPECT_GT(across, 3.0 * up) << "mean run " << across << " px across, " << up << " px up";
  ASSERT_GT(shore, 50);
  EXPECT_GT(static_cast<double>(bank) / static_cast<double>(shore), 0.9) << "the shore is drawn";
}

// water.bank_break: the bank line breaks into strokes along the shore. It only takes ink
// away (no pixel darker than with the even line), leaves a share of the shore as gaps, and
// the gaps are stretches of the shore (value noise over half a wave cell), not single pixels.
TEST_F(Water, ABrokenBankLeavesStretchesOfTheShoreBareAndInksNothingElse) {
  const mesh::Mesh m = ramp();
  const json water = {{"enabled", true}, {"level", 0.5}, {"waves", 0.0}, {"bank", 2.0}, {"spacing", 0.08}};
  const json plain = {{"shading", {{"enabled", false}}}};
  json broken_water = water;
  broken_water["bank_break"] = 1.0;
  const Picture even = paint(waterScene(water, plain), m, 200.0, 1.8);
  const Picture broken = paint(waterScene(broken_water, plain), m, 200.0, 1.8);
  const double paper = waterScene(water).output.paper.x;
  std::vector<std::pair<float, bool>> shore;  // world y along the shore, drawn
  long drawn_even = 0;
  for (int y = 1; y + 1 < kHeight; ++y) {
    for (int x = 1; x + 1 < kWidth; ++x) {
      for (int c = 0; c < 3; ++c)
        ASSERT_GE(broken.colour.at(x, y, c), even.colour.at(x, y, c) - 1.0f / 255) << x << "," << y;
      const image::Image& pos = even.position;
      if (pos.at(x, y, 3) < 0.5f || pos.at(x, y, 2) < 0.0f) continue;
      if (pos.at(x + 1, y, 2) < 0.0f || pos.at(x - 1, y, 2) < 0.0f || pos.at(x, y + 1, 2) < 0.0f ||
          pos.at(x, y - 1, 2) < 0.0f) {
        drawn_even += even.colour.at(x, y, 0) < paper - 0.25;
        shore.emplace_back(pos.at(x, y, 1), broken.colour.at(x, y, 0) < paper - 0.25);
      }
    }
  }
  ASSERT_GT(shore.size(), 100u);
  const double n = static_cast<double>(shore.size());
  EXPECT_GT(static_cast<double>(drawn_even) / n, 0.9) << "the even line draws the shore";
  long drawn = 0, switches = 0;
  std::sort(shore.begin(), shore.end());
  for (std::size_t i = 0; i < shore.size(); ++i) {
    drawn += shore[i].second;
    if (i > 0 && shore[i].second != shore[i - 1].second) ++switches;
  }
  EXPECT_GT(drawn / n, 0.45) << "most of the shore is still drawn";
  EXPECT_LT(drawn / n, 0.85) << "a share of it is left bare";
  EXPECT_GE(switches, 4) << "several gaps";
  EXPECT_LT(switches, n / 6) << "stretches, not scattered pixels";
}

// A wave thinner than two pixels is one stroke, not a row of dashes. The strokes are
// 0.7-1.6 cells long, over 10 pixels at this framing, and each is one 8-connected dark mark:
// few dark pixels lie in marks under 6 pixels across. (A test of each pixel's centre alone
// broke a thin wave wherever it bent across a row: 66 % of the dark pixels were in such
// dashes; drawn by coverage 13 %, the far strokes that are short on screen.)
TEST_F(Water, AThinWaveIsOneStrokeNotDashes) {
  const mesh::Mesh m = ramp();
  // bank 0: the strokes' least thickness, 1.6 pixels.
  const scene::Scene s =
      waterScene({{"enabled", true}, {"level", 0.5}, {"waves", 0.6}, {"ink", 1.0}, {"bank", 0.0}, {"spacing", 0.08}},
                 {{"shading", {{"enabled", false}}}});
  const Picture p = paint(s, m, 200.0, 1.8);
  std::vector<char> dark(static_cast<std::size_t>(kWidth) * kHeight, 0);
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      dark[static_cast<std::size_t>(y) * kWidth + x] = p.position.at(x, y, 3) > 0.5f &&
                                                       p.position.at(x, y, 2) < -2.0f &&
                                                       p.colour.at(x, y, 0) < s.output.paper.x - 0.2;
  int in_dashes = 0, all = 0;
  std::vector<int> stack;
  for (int i = 0; i < kWidth * kHeight; ++i) {
    if (!dark[i]) continue;
    dark[i] = 0;
    stack.push_back(i);
    int left = kWidth, right = -1, pixels = 0;
    while (!stack.empty()) {
      const int j = stack.back();
      stack.pop_back();
      left = std::min(left, j % kWidth);
      right = std::max(right, j % kWidth);
      ++pixels;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = j % kWidth + dx, y = j / kWidth + dy;
          if (x < 0 || y < 0 || x >= kWidth || y >= kHeight || !dark[y * kWidth + x]) continue;
          dark[y * kWidth + x] = 0;
          stack.push_back(y * kWidth + x);
        }
    }
    all += pixels;
    if (right - left < 6) in_dashes += pixels;
  }
  ASSERT_GT(all, 300) << "waves are drawn";
  EXPECT_LT(in_dashes, 0.3 * all) << in_dashes << " of " << all << " dark pixels in marks under 6 pixels across";
}

TEST_F(Water, ASceneWithoutWaterBuildsNoWaterCode) {
  const mesh::Mesh m = ramp();
  const scene::Scene dry = waterScene({{"enabled", false}, {"level", 0.9}});
  InkRenderer a(dry, test::prepare(dry, m));
  for (const std::string& v : a.variants().at("ink")) EXPECT_EQ(v.find("WATER"), std::string::npos) << v;
  const scene::Scene wet = waterScene({{"enabled", true}});
  InkRenderer b(wet, test::prepare(wet, m));
  EXPECT_NE(b.variants().at("ink").front().find("WATER"), std::string::npos);
}

TEST_F(Water, NothingGrowsUnderWater) {
  const mesh::Mesh m = ramp();
  const scene::Scene s = waterScene({{"enabled", true}, {"level", 0.5}},
                                    {{"shading", {{"enabled", false}}}, {"dots", {{"enabled", true}, {"size", 24.0}}}});
  std::vector<scene::LoadedObject> loaded = test::prepare(s, m);
  auto set = std::make_shared<scene::ElementSet>();
  for (double x : {40.0, 160.0}) {  // z = -30 (under) and z = 30 (above)
    elements::Instance dot;
    dot.position = glm::vec3(static_cast<float>(x), 100.0f, static_cast<float>(0.5 * (x - 100.0)));
    dot.kind = elements::Kind::MossDot;
    dot.size = 1.0f;
    dot.seed = 7;
    set->instances.push_back(dot);
  }
  loaded[0].elements = std::move(set);
  InkRenderer r(s, loaded);
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), static_cast<double>(kWidth) / kHeight, {200, 35, 1.0});
  r.render(cam, kWidth, kHeight);
  const image::Image ink = r.passTarget("elements")->colour(0).download(2);
  const image::Image pos = r.worldPositions();
  double under = 0.0, above = 0.0;
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      (pos.at(x, y, 0) < 100.0f ? under : above) += ink.at(x, y, 0);
    }
  }
  EXPECT_GT(above, 5.0) << "the dot on land is drawn";
  EXPECT_EQ(under, 0.0) << "the dot under water is not";
}

}  // namespace
}  // namespace shanshui::render
