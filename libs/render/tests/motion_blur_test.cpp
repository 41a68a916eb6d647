// Motion blur (issue 26, seed 004) against what is known in advance: the velocity buffer
// of a spinning or moving object is the projected motion of its points over one interval
// (computed here from the world positions), a still scene has none; the trail behind a
// moving square is k × its speed long; a still object nearby is not touched.
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "gl_test.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene_assets.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using nlohmann::json;

class MotionBlur : public test::HeadlessGl {};

std::vector<scene::LoadedObject> load(const scene::Scene& s, const std::vector<mesh::Mesh>& meshes) {
  std::vector<scene::LoadedObject> out;
  for (std::size_t i = 0; i < meshes.size(); ++i)
    out.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(meshes[i], s.objects[i])), nullptr});
  return out;
}

json plainObject(const char* name) {
  return {{"mesh", name}, {"up", "z"}, {"lines", {{"enabled", false}}}, {"shading", {{"enabled", false}}}};
}

// Pixel of a world point, GL's convention (y up), as the velocity buffer measures.
glm::dvec2 glPixel(const glm::dmat4& vp, glm::dvec3 p, int w, int h) {
  const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
  return (glm::dvec2(c) / c.w * 0.5 + 0.5) * glm::dvec2(w, h);
}

TEST_F(MotionBlur, VelocityIsTheProjectedMotionOfEachPointOverOneInterval) {
  const double interval = 0.05;
  enum class Motion { Spin, Velocity, Path };
  for (const Motion motion : {Motion::Spin, Motion::Velocity, Motion::Path}) {
    json o = plainObject("sphere");
    // Where the sphere's centre is now, and how far a point moved over the last interval
    // (translations); a spin turns about the centre.
    double time = 0.4;
    glm::dvec3 centre(0.0), moved(0.0);
    switch (motion) {
      case Motion::Spin:
        o["spin"] = 90.0;
        break;
      case Motion::Velocity:
        o["velocity"] = {1.5, 0.0, 0.0};
        centre = glm::dvec3(1.5 * time, 0, 0);
        moved = glm::dvec3(1.5 * interval, 0, 0);
        break;
      case Motion::Path:
        // Up y to (0, 0.6) by 0.3 s, then along x to (0.9, 0.6) by 0.6 s. At 0.32 s the
        // last interval turns the corner: from (0, 0.54) at 0.27 s to (0.06, 0.6).
        o["path"] = json::array({{{"time", 0.0}, {"offset", {0, 0, 0}}},
                                 {{"time", 0.3}, {"offset", {0, 0.6, 0}}},
                                 {{"time", 0.6}, {"offset", {0.9, 0.6, 0}}}});
        time = 0.32;
        centre = glm::dvec3(0.06, 0.6, 0);
        moved = glm::dvec3(0.06, 0.06, 0);
        break;
    }
    SCOPED_TRACE(motion == Motion::Spin       ? "spinning about z"
                 : motion == Motion::Velocity ? "moving along x"
                                              : "along a path");
    const json j = {{"objects", json::array({o})}, {"motion_blur", {{"enabled", true}, {"interval", interval}}}};
    const scene::Scene s = scene::parseScene(j, "test", ".");
    InkRenderer r(s, load(s, {test::uvSphere(1.0)}));
    EXPECT_NE(r.variants().at("gbuffer").front().find("VELOCITY"), std::string::npos);
    const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {30, 35, 0.8});
    const int size = 128;
    r.render(cam, size, size, nullptr, true, time);
    const image::Image velocity = r.passTarget("gbuffer")->colour(2).download(4);
    const image::Image world = r.worldPositions();
    const glm::dmat4 vp = glm::dmat4(cam.projection(1.0)) * glm::dmat4(cam.view());
    double worst = 0.0, largest = 0.0, off_centre = 0.0;
    int surface = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (world.at(x, y, 3) < 0.5) {
          EXPECT_EQ(velocity.at(x, y, 3), 0.0f) << "no surface, no velocity";
          continue;
        }
        const glm::dvec3 now(world.at(x, y, 0), world.at(x, y, 1), world.at(x, y, 2));
        off_centre = std::max(off_centre, std::abs(glm::length(now - centre) - 1.0));
        glm::dvec3 before = now - moved;
        if (motion == Motion::Spin) {
          const glm::dmat4 back = glm::rotate(glm::dmat4(1.0), glm::radians(-90.0 * interval), glm::dvec3(0, 0, 1));
          before = centre + glm::dvec3(back * glm::dvec4(now - centre, 1.0));
        }
        const glm::dvec2 expected = glPixel(vp, now, size, size) - glPixel(vp, before, size, size);
        const glm::dvec2 got(velocity.at(x, y, 0), velocity.at(x, y, 1));
        worst = std::max(worst, glm::length(got - expected));
        largest = std::max(largest, glm::length(expected));
        ++surface;
      }
    ASSERT_GT(surface, 2000);
    EXPECT_LT(off_centre, 0.02) << "the sphere stands where its motion puts it";
    EXPECT_GT(largest, 1.0) << "the motion is measurable";
    EXPECT_LT(worst, 0.05 * largest + 0.02);
  }
}

// A still object seen from a moving camera: each point's velocity is the difference of its
// projections through the camera now and the camera an interval ago.
TEST_F(MotionBlur, AMovingCameraGivesEachPointItsProjectedMotion) {
  const json j = {{"objects", json::array({plainObject("sphere")})}, {"motion_blur", {{"enabled", true}}}};
  const scene::Scene s = scene::parseScene(j, "test", ".");
  InkRenderer r(s, load(s, {test::uvSphere(1.0)}));
  const OrbitCamera now = sceneCamera(s, r.worldBounds(), 1.0, {30, 35, 0.8});
  OrbitCamera before = now;
  before.azimuth_deg -= 10.0;
  before.elevation_deg += 4.0;
  const int size = 128;
  r.render(now, size, size, nullptr, true, 0.0, &before);
  const image::Image velocity = r.passTarget("gbuffer")->colour(2).download(4);
  const image::Image world = r.worldPositions();
  const glm::dmat4 a = glm::dmat4(now.projection(1.0)) * glm::dmat4(now.view());
  const glm::dmat4 b = glm::dmat4(before.projection(1.0)) * glm::dmat4(before.view());
  double worst = 0.0, largest = 0.0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (world.at(x, y, 3) < 0.5) continue;
      const glm::dvec3 p(world.at(x, y, 0), world.at(x, y, 1), world.at(x, y, 2));
      const glm::dvec2 expected = glPixel(a, p, size, size) - glPixel(b, p, size, size);
      worst = std::max(worst, glm::length(glm::dvec2(velocity.at(x, y, 0), velocity.at(x, y, 1)) - expected));
      largest = std::max(largest, glm::length(expected));
    }
  EXPECT_GT(largest, 2.0);
  EXPECT_LT(worst, 0.05 * largest + 0.02);
}

TEST_F(MotionBlur, AStillSceneHasNoVelocityAndIsNotBlurred) {
  const json j = {{"objects", json::array({plainObject("sphere")})}, {"motion_blur", {{"enabled", true}}}};
  const scene::Scene s = scene::parseScene(j, "test", ".");
  json off = j;
  off.erase("motion_blur");
  const scene::Scene s0 = scene::parseScene(off, "test", ".");
  InkRenderer r(s, load(s, {test::uvSphere(1.0)})), r0(s0, load(s0, {test::uvSphere(1.0)}));
  EXPECT_TRUE(std::find(r.passesBuilt().begin(), r.passesBuilt().end(), "motion_blur") != r.passesBuilt().end());
  EXPECT_TRUE(std::find(r0.passesBuilt().begin(), r0.passesBuilt().end(), "motion_blur") == r0.passesBuilt().end());
  EXPECT_EQ(r0.variants().at("gbuffer").front().find("VELOCITY"), std::string::npos);
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {30, 35, 1.0});
  const image::Image a = r.render(cam, 96, 96).colour(0).download(3);
  const image::Image velocity = r.passTarget("gbuffer")->colour(2).download(4);
  for (std::size_t i = 0; i < velocity.pixels.size(); i += 4) {
    EXPECT_EQ(velocity.pixels[i], 0.0f);
    EXPECT_EQ(velocity.pixels[i + 1], 0.0f);
  }
  EXPECT_EQ(a.pixels, r0.render(cam, 96, 96).colour(0).download(3).pixels);
}

// A dark square moving along +x over paper, seen from above, with paint and water that last
// the whole trail: the trail behind it is k × |v| long, for two speeds and two k; a still
// square beside it is drawn exactly as without motion blur.
TEST_F(MotionBlur, TheTrailIsLengthTimesSpeedAndStillObjectsAreUntouched) {
  const mesh::Mesh square = mesh::heightGrid(9, 9, 0.125, [](double, double) { return 0.0; });
  for (const auto& [speed, k] : {std::pair{4.0, 3.0}, std::pair{8.0, 3.0}, std::pair{4.0, 6.0}}) {
    SCOPED_TRACE(testing::Message() << "speed " << speed << ", k " << k);
    json moving = plainObject("moving"), still = plainObject("still");
    moving["lines"]["bg_color"] = {0.2, 0.2, 0.2};
    still["lines"]["bg_color"] = {0.2, 0.2, 0.2};
    moving["velocity"] = {speed, 0.0, 0.0};
    still["transform"] = {{"translate", {0.0, -2.5, 0.0}}};
    const json j = {{"objects", json::array({moving, still})},
                    {"output", {{"fade", 0.0}}},
                    {"motion_blur",
                     {{"enabled", true},
                      {"interval", 0.05},
                      {"length", k},
                      {"paint", 1.0},
                      {"water", 1.0},
                      {"bristles", 0.0},
                      {"granulation", 0.0}}}};
    const scene::Scene s = scene::parseScene(j, "test", ".");
    json off = j;
    off.erase("motion_blur");
    const scene::Scene s0 = scene::parseScene(off, "test", ".");
    InkRenderer r(s, load(s, {square, square})), r0(s0, load(s0, {square, square}));
    const int size = 256;
    OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {-90, 90, 0.5});  // world +x to the right
    cam.target = glm::dvec3(0.0, -1.25, 0.0);
    const image::Image with = r.render(cam, size, size, nullptr, true, 0.0).colour(0).download(3);
    const image::Image velocity = r.passTarget("gbuffer")->colour(2).download(4);
    const image::Image without = r0.render(cam, size, size, nullptr, true, 0.0).colour(0).download(3);
    const image::Image world = r0.worldPositions();
    // The moving square's rows and its speed in pixels per interval, from the buffer.
    double v = 0.0;
    int left = size, top = size, bottom = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        if (velocity.at(x, y, 3) > 0.5 && std::abs(velocity.at(x, y, 0)) > 0.1) {
          v = std::max(v, static_cast<double>(std::abs(velocity.at(x, y, 0))));
          left = std::min(left, x), top = std::min(top, y), bottom = std::max(bottom, y);
        }
    ASSERT_GT(v, 1.0);
    ASSERT_GT(bottom - top, 20);
    std::vector<double> lengths;
    for (int y = top + 4; y <= bottom - 4; ++y) {
      int x = left - 1;
      while (x >= 0 && with.at(x, y, 1) < without.at(x, y, 1) - 0.1) --x;
      lengths.push_back(left - 1 - x);
    }
    std::nth_element(lengths.begin(), lengths.begin() + lengths.size() / 2, lengths.end());
    EXPECT_NEAR(lengths[lengths.size() / 2], k * v, 2.0) << "|v| = " << v << " px";
    // The still square and the paper around it: as without blur.
    int stillPixels = 0, changed = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (world.at(x, y, 3) < 0.5 || world.at(x, y, 1) > -1.0) continue;
        ++stillPixels;
        for (int c = 0; c < 3; ++c) changed += with.at(x, y, c) != without.at(x, y, c);
      }
    EXPECT_GT(stillPixels, 1000);
    EXPECT_EQ(changed, 0);
  }
}

// Animated frames redraw only the region the moving objects cover now and covered in the
// last frame; every frame equals the one a fresh renderer draws in full, with every pass
// that can run (canvas, lines as strokes, shading, mist, a dissolving border, brush strokes,
// pigment, edges, ink diffusion, substrate, motion blur).
TEST_F(MotionBlur, AnimatedFramesRedrawOnlyWhatMovedAndMatchAFullRedraw) {
  json still = {{"mesh", "ground"},
                {"up", "z"},
                {"strokes", {{"style", "liuye"}}},
                {"pigment", {{"name", "ochre"}}},
                {"lines", {{"width", 3.0}}},
                {"border", {{"mode", "dissolve"}}}};
  json ball = {{"mesh", "ball"}, {"up", "z"}, {"velocity", {0.8, 0.0, 0.0}}, {"spin", 40.0}};
  ball["transform"] = {{"scale", {0.3, 0.3, 0.3}}, {"translate", {-1.0, 0.0, 0.8}}};
  const json j = {{"objects", json::array({still, ball})},
                  {"canvas", {{"type", "rice_paper"}}},
                  {"mist", {{"density", 0.6}, {"height", 0.3}}},
                  {"edges", {{"enabled", true}}},
                  {"diffusion", {{"ring_steps", 3}, {"iterations", 5}, {"absorb", 0.6}}},
                  {"substrate", {{"enabled", true}}},
                  {"motion_blur", {{"enabled", true}, {"interval", 0.1}}}};
  const scene::Scene s = scene::parseScene(j, "test", ".");
  const mesh::Mesh ground = mesh::heightGrid(
      33, 33, 0.1, [](double x, double y) { return 0.3 * std::sin(2.0 * x) * std::cos(1.5 * y); },
      glm::dvec3(-1.6, -1.6, 0.0));
  const std::vector<mesh::Mesh> meshes{ground, test::uvSphere(1.0)};
  InkRenderer r(s, load(s, meshes));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 4.0 / 3.0, {-30, 35, 1.0});
  const int w = 160, h = 120;
  for (int frame = 0; frame < 4; ++frame) {
    SCOPED_TRACE(testing::Message() << "frame " << frame);
    const double time = 0.1 * frame;
    FrameStats st;
    const image::Image continued = r.render(cam, w, h, &st, true, time).colour(0).download(3);
    if (frame > 0) {
      EXPECT_LT(st.redrawn, 0.6) << "only the moving ball's region";
      EXPECT_GT(st.redrawn, 0.0);
    }
    InkRenderer fresh(s, load(s, meshes));
    FrameStats full;
    const image::Image expected = fresh.render(cam, w, h, &full, true, time).colour(0).download(3);
    EXPECT_EQ(full.redrawn, 1.0);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < expected.pixels.size(); ++i)
      differ += std::abs(expected.pixels[i] - continued.pixels[i]) > 1.5f / 255;
    EXPECT_EQ(differ, 0u);
  }
}

}  // namespace
}  // namespace shanshui::render
