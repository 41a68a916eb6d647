// Camera placement against geometry: framing by projecting the box's corners, the relief
// grid against a brute-force maximum, and the high-distance camera against where it must
// stand (on the ground, outside the land) and what it must see (the summit, high in the
// frame). No GL.
#include "shanshui/render/camera.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

namespace shanshui::render {
namespace {

// Normalised device coordinates of a world point (x, y; z > 1 or w <= 0 means not visible).
glm::dvec3 project(const OrbitCamera& cam, double aspect, const glm::dvec3& p) {
  const glm::dvec4 c = glm::dmat4(cam.projection(aspect)) * glm::dmat4(cam.view()) * glm::dvec4(p, 1.0);
  return glm::dvec3(c) / c.w;
}

TEST(Camera, FillBoundsHoldsEveryCornerAndTouchesTheFrameOnBothSidesOfOneAxis) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    mesh::Bounds b;
    b.min = glm::dvec3(unit(rng), unit(rng), unit(rng)) * 10.0 - 5.0;
    b.max = b.min + glm::dvec3(0.2 + 10 * unit(rng), 0.2 + 10 * unit(rng), 0.05 + 3 * unit(rng));
    const double az = 360 * unit(rng), el = -60 + 140 * unit(rng) * 0.9, aspect = 0.4 + 2 * unit(rng);
    const double fov = 15 + 50 * unit(rng);
    const OrbitCamera cam = fillBounds(b, az, el, fov, aspect);
    glm::dvec2 lo(1e9), hi(-1e9);
    for (int i = 0; i < 8; ++i) {
      const glm::dvec3 ndc = project(cam, aspect, b.corner(i));
      ASSERT_GT(ndc.z, -1.0) << "corner in front of the near plane, trial " << trial;
      ASSERT_LT(ndc.z, 1.0) << "corner past the far plane, trial " << trial;
      lo = glm::min(lo, glm::dvec2(ndc));
      hi = glm::max(hi, glm::dvec2(ndc));
    }
    // Every corner inside the 94 % margin; one axis touches it on both sides, the other is
    // centred.
    EXPECT_LE(std::max({-lo.x, -lo.y, hi.x, hi.y}), 0.94 + 1e-6) << "trial " << trial;
    const bool x_tight = std::abs(hi.x - 0.94) < 1e-4 && std::abs(lo.x + 0.94) < 1e-4;
    const bool y_tight = std::abs(hi.y - 0.94) < 1e-4 && std::abs(lo.y + 0.94) < 1e-4;
    EXPECT_TRUE(x_tight || y_tight) << "trial " << trial << ": x [" << lo.x << ", " << hi.x << "] y [" << lo.y << ", "
                                    << hi.y << "]";
    EXPECT_NEAR(lo.x + hi.x, 0.0, 1e-4) << "trial " << trial;
    EXPECT_NEAR(lo.y + hi.y, 0.0, 1e-4) << "trial " << trial;
  }
}

// A Gaussian peak of height 1 (σ = 1.5) on a 10 × 10 plain raised to 0.2 on its east half,
// sampled on a grid.
std::vector<glm::dvec3> peakOnAPlain(glm::dvec2 peak) {
  std::vector<glm::dvec3> points;
  for (int j = 0; j <= 100; ++j) {
    for (int i = 0; i <= 100; ++i) {
      const glm::dvec2 xy(-5 + 0.1 * i, -5 + 0.1 * j);
      const double r2 = glm::dot(xy - peak, xy - peak);
      points.emplace_back(xy, std::exp(-r2 / (2 * 1.5 * 1.5)) + (xy.x > 0 ? 0.2 : 0.0));
    }
  }
  return points;
}

// The drawn framing bisects over the hull candidates instead of every point. Oracle: the
// largest and smallest ratio (x − m) / (z − e) over all points, brute force, for random
// m and e (below the points), on a disc of points, a grid (many points on the polygon's
// edges), a few points, the disc with a far outlier, a line and one point repeated; and the filter must leave few of a
// disc's points, or it saves nothing.
TEST(Camera, HullCandidatesKeepEveryExtremeOfARatio) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<glm::dvec2>> sets(3);
  for (int i = 0; i < 10000; ++i) {
    const double r = std::sqrt(unit(rng)), a = 6.283185307179586 * unit(rng);
    sets[0].emplace_back(3 * r * std::cos(a), 5 + 2 * r * std::sin(a));
  }
  for (int j = 0; j <= 60; ++j)
    for (int i = 0; i <= 60; ++i) sets[1].emplace_back(-3 + 0.1 * i, 4 + 0.05 * j);
  sets[2] = {{0, 4}, {1, 5}, {0.5, 4.5}, {-1, 6}, {0.2, 4.1}, {0.3, 5.2}, {0.1, 4.9}, {-0.4, 5.5}, {0.6, 4.4}, {0, 5}};
  // A far outlier (most directions share it), points on a line, and one point many times.
  sets.push_back(sets[0]);
  sets.back().emplace_back(40, 6);
  sets.push_back({});
  for (int i = 0; i < 40; ++i) sets.back().emplace_back(0.1 * i, 4 + 0.05 * i);
  sets.push_back(std::vector<glm::dvec2>(40, glm::dvec2(1, 5)));
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const std::vector<glm::dvec2>& all = sets[k];
    const std::vector<glm::dvec2> kept = hullCandidates(all);
    if (k == 0) {
      EXPECT_LT(kept.size(), all.size() / 20) << "a disc keeps only its rim";
    }
    for (int trial = 0; trial < 200; ++trial) {
      const double m = -4 + 8 * unit(rng), e = 2.9 * unit(rng);  // below every point's z
      auto extremes = [&](const std::vector<glm::dvec2>& v) {
        double most = -1e300, least = 1e300;
        for (const glm::dvec2& p : v) {
          const double s = (p.x - m) / (p.y - e);
          most = std::max(most, s);
          least = std::min(least, s);
        }
        return glm::dvec2(most, least);
      };
      EXPECT_EQ(extremes(kept), extremes(all)) << "set " << k << ", trial " << trial;
    }
  }
}

TEST(Camera, ReliefGroundIsTheHighestPointOfTheCellsNearby) {
  const std::vector<glm::dvec3> points = peakOnAPlain({1, -1});
  const Relief relief(points, 16);
  EXPECT_LT(glm::length(relief.summit() - glm::dvec3(1, -1, 1.2)), 1e-9);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-6.0, 6.0);
  for (int trial = 0; trial < 200; ++trial) {
    const glm::dvec2 at(coord(rng), coord(rng));
    const double radius = 0.5;
    // Brute force: the cells the disc's square touches hold every point within radius, and
    // none farther than the square's corner plus a cell diagonal.
    double within = relief.bounds().min.z, near = relief.bounds().min.z;
    const double cell = 10.0 / 16 * std::sqrt(2.0);
    for (const glm::dvec3& p : points) {
      const double d = glm::length(glm::dvec2(p) - at);
      if (d <= radius) within = std::max(within, p.z);
      if (d <= radius * std::sqrt(2.0) + cell) near = std::max(near, p.z);
    }
    const double g = relief.groundAt(at, radius);
    EXPECT_GE(g, within) << at.x << ", " << at.y;
    EXPECT_LE(g, near) << at.x << ", " << at.y;
  }
}

TEST(Camera, HighDistanceStandsOnTheGroundOutsideTheLandAndSeesTheSummitHighInTheFrame) {
  for (const glm::dvec2 peak : {glm::dvec2(0, 0), glm::dvec2(3, 2), glm::dvec2(-4, 4)}) {
    const Relief relief(peakOnAPlain(peak));
    for (double az = 0; az < 360; az += 45) {
      const OrbitCamera cam = highDistance(relief, az, 40.0, 1.0);
      const double aspect = 0.4;
      const glm::dvec3 eye = cam.eye();
      SCOPED_TRACE(testing::Message() << "peak " << peak.x << ", " << peak.y << " azimuth " << az);
      // On the ground: above it, and below the summit (looking up).
      EXPECT_GT(eye.z, relief.groundAt(glm::dvec2(eye), 0.1));
      const glm::dvec2 edge = glm::clamp(glm::dvec2(eye), glm::dvec2(-5), glm::dvec2(5));
      EXPECT_GT(eye.z, relief.groundAt(edge, 0.1)) << "below the land's edge: the underside shows";
      EXPECT_LT(eye.z, relief.summit().z);
      EXPECT_LT(cam.elevation_deg, 0.0) << "the view tilts up";
      // Outside the land's bounds, on the side the azimuth names.
      EXPECT_TRUE(eye.x < -5 || eye.x > 5 || eye.y < -5 || eye.y > 5) << eye.x << ", " << eye.y;
      const double side =
          glm::dot(glm::dvec2(eye) - peak, glm::dvec2(std::cos(glm::radians(az)), std::sin(glm::radians(az))));
      EXPECT_GT(side, 0.0);
      // The summit is in the frame's upper part, centred across.
      const glm::dvec3 s = project(cam, aspect, relief.summit());
      EXPECT_NEAR(s.x, 0.0, 1e-6);
      EXPECT_GT(s.y, 0.4);
      EXPECT_LT(s.y, 0.95);
      EXPECT_GT(s.z, -1.0);
      EXPECT_LT(s.z, 1.0);
      // Zooming narrows the field and keeps the summit in the frame.
      const OrbitCamera closer = highDistance(relief, az, 40.0, 1.5);
      EXPECT_LT(closer.fov_y_deg, cam.fov_y_deg);
      EXPECT_LT(glm::length(closer.eye() - eye), 1e-9);
    }
  }
}

}  // namespace
}  // namespace shanshui::render
