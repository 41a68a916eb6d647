// Objects standing on a terrain (objects.N.ground): the resting pose against analytic
// grounds (a level plane, an inclined plane, a Gaussian hill) and the site rules against
// where the analytic surface has its summit and meets the water.
#include "shanshui/scene/grounding.h"

#include <cmath>

#include <gtest/gtest.h>

#include "shanshui/core/error.h"
#include "shanshui/mesh/shapes.h"

namespace shanshui::scene {
namespace {

// A ground of 401 m a side (x, y in [-200, 200]) with heights h(x, y), and a box 4 x 2 m,
// 3 m high, that stands on it.
template <typename H>
LoadedObject groundOf(H h) {
  auto a = std::make_shared<ObjectAsset>();
  a->mesh = mesh::heightGrid(
      201, 201, 2.0, [&](double x, double y) { return h(x - 200.0, y - 200.0); }, glm::dvec3(-200.0, -200.0, 0.0));
  a->bounds = mesh::bounds(a->mesh);
  return {a, nullptr, nullptr};
}

LoadedObject box() {
  auto a = std::make_shared<ObjectAsset>();
  a->mesh = mesh::unitCube();
  for (glm::dvec3& p : a->mesh.positions) p = (p - glm::dvec3(0.5)) * glm::dvec3(4.0, 2.0, 3.0);
  a->bounds = mesh::bounds(a->mesh);
  return {a, nullptr, nullptr};
}

Scene twoObjects(GroundSite site, glm::dvec2 at) {
  Scene s;
  s.objects.resize(2);
  s.objects[0].name = "land";
  s.objects[0].dem = "land.asc";
  s.objects[1].name = "hut";
  s.objects[1].mesh = "hut.obj";
  s.objects[1].ground.on = "land";
  s.objects[1].ground.site = site;
  s.objects[1].ground.sink = 0.0;
  s.objects[1].transform.translate = glm::dvec3(at, 0.0);
  return s;
}

// The box's world corners under its resolved matrix.
mesh::Bounds placedBox(const glm::dmat4& m, const ObjectAsset& a) {
  mesh::Bounds b{glm::dvec3(1e300), glm::dvec3(-1e300)};
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 w(m * glm::dvec4(a.bounds.corner(c), 1.0));
    b.min = glm::min(b.min, w);
    b.max = glm::max(b.max, w);
  }
  return b;
}

TEST(Grounding, AModelPlacedAtXYRestsOnALevelGroundThere) {
  const std::vector<LoadedObject> loaded{groundOf([](double, double) { return 12.5; }), box()};
  Scene s = twoObjects(GroundSite::At, {31.0, -47.0});
  s.objects[0].transform.translate = {0.0, 0.0, 100.0};  // the ground moved up: the box follows
  const glm::dmat4 m = Grounding(loaded).worldMatrices(s)[1];
  const mesh::Bounds b = placedBox(m, *loaded[1].geometry);
  EXPECT_NEAR(b.min.z, 112.5, 1e-9);
  EXPECT_NEAR(b.size().z, 3.0, 1e-9);
  EXPECT_NEAR(b.centre().x, 31.0, 1e-9);
  EXPECT_NEAR(b.centre().y, -47.0, 1e-9);
  // translate.z lifts it; sink lowers it by a share of its height.
  s.objects[1].transform.translate.z = 2.0;
  s.objects[1].ground.sink = 0.1;
  EXPECT_NEAR(placedBox(Grounding(loaded).worldMatrices(s)[1], *loaded[1].geometry).min.z, 112.5 + 2.0 - 0.3, 1e-9);
}

TEST(Grounding, UprightOnASlopeNothingFloatsAndTiltedItLiesOnIt) {
  const double g = 0.25;  // dz/dx: 14 degrees
  const std::vector<LoadedObject> loaded{groundOf([&](double x, double) { return g * x; }), box()};
  Scene s = twoObjects(GroundSite::At, {40.0, 10.0});
  Grounding grounding(loaded);
  // Upright: the base goes down to the lowest ground under the footprint (x − 2 m).
  const mesh::Bounds up = placedBox(grounding.worldMatrices(s)[1], *loaded[1].geometry);
  EXPECT_NEAR(up.min.z, g * (40.0 - 2.0), 1e-6);
  EXPECT_NEAR(up.size().z, 3.0, 1e-9);
  // Tilted: the box's up axis is the plane's normal and its base's centre on the plane.
  s.objects[1].ground.align = 1.0;
  const glm::dmat4 m = grounding.worldMatrices(s)[1];
  const glm::dvec3 axis = glm::normalize(glm::dvec3(m * glm::dvec4(0.0, 0.0, 1.0, 0.0)));
  const glm::dvec3 normal = glm::normalize(glm::dvec3(-g, 0.0, 1.0));
  EXPECT_GT(glm::dot(axis, normal), std::cos(glm::radians(0.5)));
  const glm::dvec3 base(m * glm::dvec4(0.0, 0.0, loaded[1].geometry->bounds.min.z, 1.0));
  EXPECT_NEAR(base.z, g * base.x, 0.05);
}

TEST(Grounding, TheSummitRuleFindsTheHighestFlatGround) {
  // Two Gaussian hills; the higher at (60, -30).
  auto h = [](double x, double y) {
    return 80.0 * std::exp(-((x - 60) * (x - 60) + (y + 30) * (y + 30)) / 3000.0) +
           50.0 * std::exp(-((x + 90) * (x + 90) + (y - 80) * (y - 80)) / 2000.0);
  };
  const std::vector<LoadedObject> loaded{groundOf(h), box()};
  Scene s = twoObjects(GroundSite::Summit, {0.0, 0.0});
  s.objects[0].border.mode = BorderMode::Keep;
  const mesh::Bounds b = placedBox(Grounding(loaded).worldMatrices(s)[1], *loaded[1].geometry);
  const double cell = 400.0 / 96.0;  // the rule's candidate grid
  EXPECT_NEAR(b.centre().x, 60.0, cell);
  EXPECT_NEAR(b.centre().y, -30.0, cell);
  EXPECT_NEAR(b.min.z, h(b.centre().x, b.centre().y), 0.5);
}

TEST(Grounding, TheWaterEdgeRuleStandsWhereTheGroundMeetsTheWater) {
  auto h = [](double x, double y) { return 100.0 * std::exp(-(x * x + y * y) / 8000.0); };
  const std::vector<LoadedObject> loaded{groundOf(h), box(), box(), box()};
  Scene s = twoObjects(GroundSite::WaterEdge, {0.0, 0.0});
  s.objects.push_back(s.objects[1]);
  s.objects.push_back(s.objects[1]);
  s.objects[2].name = "rock";
  s.objects[3].name = "rock2";
  s.water.enabled = true;
  s.water.level = 0.4;
  const auto m = Grounding(loaded).worldMatrices(s);
  // The ground's relief runs from h at the corners (~0) to 100; the level is 40 % up it.
  const double lo = h(200.0, 200.0), level = lo + 0.4 * (100.0 - lo);
  std::vector<glm::dvec2> spots;
  for (int i = 1; i <= 3; ++i) {
    const mesh::Bounds b = placedBox(m[i], *loaded[i].geometry);
    const glm::dvec2 c(b.centre());
    EXPECT_NEAR(h(c.x, c.y), level, 0.02 * 100.0) << "object " << i;
    for (const glm::dvec2& other : spots) EXPECT_GT(glm::distance(c, other), 4.0) << "object " << i;
    spots.push_back(c);
  }
}

TEST(Grounding, ABoatOnTheWaterFloatsAtItsLevel) {
  auto h = [](double x, double y) { return 100.0 * std::exp(-(x * x + y * y) / 8000.0); };
  const std::vector<LoadedObject> loaded{groundOf(h), box()};
  Scene s = twoObjects(GroundSite::At, {150.0, -120.0});
  s.objects[1].ground.on = "water";
  s.objects[1].ground.sink = 0.2;
  EXPECT_NE(groundingProblem(s).find("needs water"), std::string::npos) << groundingProblem(s);
  s.water.enabled = true;
  s.water.level = 0.25;
  ASSERT_EQ(groundingProblem(s), "");
  const mesh::Bounds b = placedBox(Grounding(loaded).worldMatrices(s)[1], *loaded[1].geometry);
  const double lo = h(200.0, 200.0), level = lo + 0.25 * (100.0 - lo);
  EXPECT_NEAR(b.min.z, level - 0.2 * 3.0, 1e-9);
  EXPECT_NEAR(b.centre().x, 150.0, 1e-9);
}

TEST(Grounding, MistakesAreRefusedByKeyAndName) {
  const std::vector<LoadedObject> loaded{groundOf([](double, double) { return 0.0; }), box()};
  auto message = [&](const Scene& s) {
    try {
      Grounding(loaded).worldMatrices(s);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  Scene s = twoObjects(GroundSite::At, {500.0, 0.0});
  EXPECT_NE(message(s).find("objects.1.ground: (500, 0) from transform.translate is off 'land'"), std::string::npos)
      << message(s);
  s = twoObjects(GroundSite::At, {0.0, 0.0});
  s.objects[0].transform.rotate_deg.x = 10.0;
  EXPECT_NE(message(s).find("objects.1.ground.on: 'land' is tilted"), std::string::npos) << message(s);
  s = twoObjects(GroundSite::WaterEdge, {0.0, 0.0});
  EXPECT_NE(message(s).find("objects.1.ground.site: 'water_edge' needs water"), std::string::npos) << message(s);
  s = twoObjects(GroundSite::At, {0.0, 0.0});
  s.objects[1].ground.on = "lnad";
  EXPECT_EQ(groundingProblem(s), "objects.1.ground.on: 'lnad' names no object (named objects: 'land', 'hut')");
  s.objects[1].ground.on = "hut";
  EXPECT_NE(groundingProblem(s).find("is this object itself"), std::string::npos) << groundingProblem(s);
  s.objects[0].spin_deg_per_s = 5.0;
  s.objects[1].ground.on = "land";
  EXPECT_NE(groundingProblem(s).find("moves"), std::string::npos) << groundingProblem(s);
  EXPECT_TRUE(usesGrounding(twoObjects(GroundSite::At, {0, 0})));
  s.objects[1].ground.on.clear();
  EXPECT_FALSE(usesGrounding(s));
}

}  // namespace
}  // namespace shanshui::scene
