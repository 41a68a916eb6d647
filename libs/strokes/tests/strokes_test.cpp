// Object-space lines for brush strokes (seed 002), against analytic answers: a cube's 12
// creases of which 9 show from a corner and link into at most 9 strokes, a sphere's
// silhouette as one closed chain, a torus seen from above with its two silhouettes, and
// the Cardinal spline's interpolation and tension.
#include <cmath>
#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/core/error.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/strokes/brush.h"
#include "shanshui/strokes/chains.h"
#include "shanshui/strokes/edges.h"
#include "shanshui/strokes/visibility.h"
#include "test_support.h"

namespace shanshui::strokes {
namespace {

struct View {
  glm::dvec3 eye;
  glm::dmat4 vp;
};

View lookFrom(glm::dvec3 eye, glm::dvec3 at, glm::dvec3 up = {0, 0, 1}, double fovDeg = 40.0) {
  return {eye, glm::perspective(glm::radians(fovDeg), 1.0, 0.1, 100.0) * glm::lookAt(eye, at, up)};
}

TEST(Strokes, CubeHasTwelveCreasesAndNoBorder) {
  const mesh::Mesh m = mesh::unitCube();
  const EdgeGraph g = buildEdgeGraph(m);
  EXPECT_EQ(g.vertices.size(), 18u);
  EXPECT_EQ(g.non_manifold, 0u);
  int creases = 0, borders = 0;
  for (const FeatureEdge& e : featureEdges(g, m, {5, 4, 3}, 30.0)) {
    creases += (e.kinds & kCrease) != 0;
    borders += (e.kinds & kBorder) != 0;
  }
  EXPECT_EQ(creases, 12);
  EXPECT_EQ(borders, 0);
  // The printed test |N1·N2| > 0.5 would mark the six flat diagonals instead.
  int flat = 0;
  for (double d : g.normal_dot) flat += std::abs(d) > 0.5;
  EXPECT_EQ(flat, 6);
  // A crease angle past 90° keeps none of the cube's right angles.
  int steep = 0;
  for (const FeatureEdge& e : featureEdges(g, m, {5, 4, 3}, 100.0)) steep += (e.kinds & kCrease) != 0;
  EXPECT_EQ(steep, 0);
}

// From a generic corner, 3 faces show: their 9 edges (6 on the outline, 3 meeting at the
// near corner) are visible, the 3 at the far corner hidden; the outline's edges are the
// silhouettes.
TEST(Strokes, CubeFromACornerShowsNineEdgesLinkedIntoAtMostNineStrokes) {
  const mesh::Mesh m = mesh::unitCube();
  const EdgeGraph g = buildEdgeGraph(m);
  const View v = lookFrom({3.1, 2.3, 2.7}, {0.5, 0.5, 0.5});
  const std::vector<FeatureEdge> edges = featureEdges(g, m, v.eye, 30.0);
  const ReferenceImage ref = rasterizeReference(m, v.vp, 400, 400);
  const std::vector<ScreenSegment> seen = visibleSegments(edges, g, m, v.vp, ref);
  // Visible length per edge over its projected length.
  std::map<std::uint32_t, double> visible;
  for (const ScreenSegment& s : seen) visible[s.edge] += glm::length(s.b - s.a);
  int shown = 0, hidden = 0, silhouettes = 0;
  for (const FeatureEdge& e : edges) {
    if (!(e.kinds & kCrease)) continue;
    auto px = [&](std::uint32_t i) {
      const glm::dvec4 c = v.vp * glm::dvec4(m.positions[i], 1.0);
      return (glm::dvec2(c) / c.w * 0.5 + 0.5) * 400.0;
    };
    const double full = glm::length(px(g.vertices[e.edge][1]) - px(g.vertices[e.edge][0]));
    const double share = visible[e.edge] / full;
    if (share > 0.9) ++shown;
    if (share < 0.1) ++hidden;
    EXPECT_TRUE(share > 0.9 || share < 0.1) << "edge " << e.edge << " partly visible: " << share;
    silhouettes += (e.kinds & kSilhouette) != 0;
  }
  EXPECT_EQ(shown, 9);
  EXPECT_EQ(hidden, 3);
  EXPECT_EQ(silhouettes, 6);
  const std::vector<Chain> chains = linkSegments(seen);
  EXPECT_LE(chains.size(), 9u);
  EXPECT_GE(chains.size(), 1u);
  double total = 0.0;
  for (const Chain& c : chains) total += c.length_px;
  double pieces = 0.0;
  for (const ScreenSegment& s : seen) pieces += glm::length(s.b - s.a);
  EXPECT_GE(total, pieces - 1e-6);  // every visible piece is in a chain (gaps add length)
}

// Seen from above its pole, a sphere's silhouette is one latitude ring: one closed chain.
TEST(Strokes, SphereSilhouetteIsOneClosedChain) {
  const mesh::Mesh m = mesh::uvSphere(1.0, 32, 64);
  const EdgeGraph g = buildEdgeGraph(m);
  const View v = lookFrom({0, 0, 4}, {0, 0, 0}, {0, 1, 0});
  std::vector<FeatureEdge> silhouettes;
  for (const FeatureEdge& e : featureEdges(g, m, v.eye, 180.0))
    if (e.kinds & kSilhouette) silhouettes.push_back(e);
  ASSERT_EQ(silhouettes.size(), 64u);  // one ring of the 64 slices
  const ReferenceImage ref = rasterizeReference(m, v.vp, 300, 300);
  const std::vector<Chain> chains = linkSegments(visibleSegments(silhouettes, g, m, v.vp, ref));
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_TRUE(chains[0].closed);
  // Its length is the ring's projected circumference.
  glm::dvec2 centre(0.0);
  for (const glm::dvec2& p : chains[0].points) centre += p / static_cast<double>(chains[0].points.size());
  double radius = 0.0;
  for (const glm::dvec2& p : chains[0].points) radius += glm::length(p - centre) / chains[0].points.size();
  EXPECT_NEAR(chains[0].length_px, 2 * M_PI * radius, 0.01 * 2 * M_PI * radius);
}

// From above, a torus shows its outer and its inner silhouette: two closed chains, the
// inner one inside the outer.
TEST(Strokes, TorusFromAboveShowsItsInnerAndOuterSilhouettes) {
  const mesh::Mesh m = mesh::torus(3.0, 1.0, 96, 48);
  const EdgeGraph g = buildEdgeGraph(m);
  const View v = lookFrom({0, 0, 12}, {0, 0, 0}, {0, 1, 0});
  std::vector<FeatureEdge> silhouettes;
  for (const FeatureEdge& e : featureEdges(g, m, v.eye, 180.0))
    if (e.kinds & kSilhouette) silhouettes.push_back(e);
  const ReferenceImage ref = rasterizeReference(m, v.vp, 400, 400);
  const std::vector<Chain> chains = linkSegments(visibleSegments(silhouettes, g, m, v.vp, ref));
  ASSERT_EQ(chains.size(), 2u);
  std::vector<double> radii;
  for (const Chain& c : chains) {
    EXPECT_TRUE(c.closed);
    double r = 0.0;
    for (const glm::dvec2& p : c.points) r += glm::length(p - glm::dvec2(200.0)) / c.points.size();
    radii.push_back(r);
  }
  std::sort(radii.begin(), radii.end());
  // Projected radii of the rings at about 2 and 4 units, seen from 12 (less the tube's
  // rise for the perspective), against the 400 px image of a 40° field.
  const double scale = 200.0 / std::tan(glm::radians(20.0));
  EXPECT_NEAR(radii[0], scale * 2.0 / 12.0, 0.1 * scale * 2.0 / 12.0);
  EXPECT_NEAR(radii[1], scale * 4.0 / 12.0, 0.1 * scale * 4.0 / 12.0);
}

TEST(Strokes, LinkingRespectsTheTurnAndTheGap) {
  // An L of two pieces (90°): two strokes at 45°, one at 100°.
  const std::vector<ScreenSegment> ell = {{{0, 0}, {10, 0}, 0.5, 0.5, 0, kCrease},
                                          {{10, 0}, {10, 10}, 0.5, 0.5, 1, kCrease}};
  EXPECT_EQ(linkSegments(ell).size(), 2u);
  EXPECT_EQ(linkSegments(ell, {100.0, 5.0}).size(), 1u);
  // Collinear pieces 4 px apart join; 6 px apart they do not.
  const std::vector<ScreenSegment> near = {{{0, 0}, {10, 0}, 0.5, 0.5, 0, 0}, {{14, 0}, {24, 0}, 0.5, 0.5, 1, 0}};
  const std::vector<ScreenSegment> far = {{{0, 0}, {10, 0}, 0.5, 0.5, 0, 0}, {{16, 0}, {26, 0}, 0.5, 0.5, 1, 0}};
  EXPECT_EQ(linkSegments(near).size(), 1u);
  EXPECT_EQ(linkSegments(far).size(), 2u);
  // A piece stored backwards is walked forwards.
  const std::vector<ScreenSegment> reversed = {{{0, 0}, {10, 0}, 0.1, 0.2, 0, 0}, {{20, 0}, {10, 0}, 0.3, 0.2, 1, 0}};
  const std::vector<Chain> one = linkSegments(reversed);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].points.size(), 3u);
  EXPECT_EQ(one[0].depth, (std::vector<double>{0.1, 0.2, 0.3}));  // depths follow their points
  EXPECT_DOUBLE_EQ(one[0].length_px, 20.0);
  test::expectErrorNaming([] { linkSegments({}, {200.0, 5.0}); }, "turn", "200");
}

TEST(Strokes, CardinalSplinePassesThroughItsPointsAndTensionOneIsStraight) {
  Chain c;
  c.points = {{0, 0}, {10, 5}, {20, -5}, {30, 0}};
  for (const double tension : {-0.5, 0.0, 0.5, 1.0}) {
    const std::vector<glm::dvec2> curve = cardinalSpline(c, tension, 0.5);
    // Through every control point (the span starts are samples), ending on the last.
    for (const glm::dvec2& p : c.points) {
      double nearest = 1e9;
      for (const glm::dvec2& q : curve) nearest = std::min(nearest, glm::length(q - p));
      EXPECT_LT(nearest, 1e-9) << "tension " << tension;
    }
    EXPECT_EQ(curve.back(), c.points.back());
    if (tension == 1.0) {  // s = 0: each span is the straight segment (with cubic easing)
      for (const glm::dvec2& q : curve) {
        const int k = std::min(2, static_cast<int>(q.x / 10.0));
        const glm::dvec2 a = c.points[k], b = c.points[k + 1];
        EXPECT_NEAR(cross(glm::dvec3(b - a, 0), glm::dvec3(q - a, 0)).z, 0.0, 1e-9);
      }
    }
  }
  // Subdivided, no span is longer than asked and every new point lies on the polyline.
  const Chain fine = subdivided(c, 3.0);
  EXPECT_EQ(fine.points.front(), c.points.front());
  EXPECT_EQ(fine.points.back(), c.points.back());
  for (std::size_t i = 1; i < fine.points.size(); ++i)
    EXPECT_LE(glm::length(fine.points[i] - fine.points[i - 1]), 3.0 + 1e-9);
  for (const glm::dvec2& q : fine.points) {
    const int k = std::min(2, static_cast<int>(q.x / 10.0));
    const glm::dvec2 a = c.points[k], b = c.points[k + 1];
    EXPECT_NEAR(cross(glm::dvec3(b - a, 0), glm::dvec3(q - a, 0)).z, 0.0, 1e-9);
  }
  // Closed: wraps and ends where it began.
  c.closed = true;
  const std::vector<glm::dvec2> loop = cardinalSpline(c, 0.0, 1.0);
  EXPECT_EQ(loop.front(), loop.back());
  test::expectErrorNaming([&] { cardinalSpline(c, 2.0, 1.0); }, "tension", "2");
}

// Pixel centres of a column covered by the strip's triangles, by brute force.
double coveredHeight(const std::vector<StripVertex>& strip, double x) {
  int covered = 0;
  for (int yi = -200; yi <= 200; ++yi) {
    const glm::dvec2 q(x, yi * 0.05);
    bool in = false;
    for (std::size_t i = 0; i + 2 < strip.size() && !in; ++i) {
      const glm::dvec2 a = strip[i].position, b = strip[i + 1].position, c = strip[i + 2].position;
      const double d1 = cross(glm::dvec3(b - a, 0), glm::dvec3(q - a, 0)).z;
      const double d2 = cross(glm::dvec3(c - b, 0), glm::dvec3(q - b, 0)).z;
      const double d3 = cross(glm::dvec3(a - c, 0), glm::dvec3(q - c, 0)).z;
      in = (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
    }
    covered += in;
  }
  return covered * 0.05;
}

// The strip's width, measured across it, follows width · (min + (1 − min) · pressure).
TEST(Brush, StrokeWidthFollowsThePressureCurve) {
  std::vector<glm::dvec2> path;
  for (int i = 0; i <= 200; ++i) path.emplace_back(i, 0.0);
  BrushOptions o;
  o.width_px = 8.0;
  for (StrokeStyle style : {StrokeStyle::Qinxian, StrokeStyle::Liuye, StrokeStyle::Zaohe, StrokeStyle::Jianbi,
                            StrokeStyle::Zhuye, StrokeStyle::Mixed}) {
    SCOPED_TRACE(static_cast<int>(style));
    const std::vector<StripVertex> strip = strokeStrip(path, style, 7, o);
    ASSERT_EQ(strip.size(), 2 * path.size());
    for (double x = 5.5; x < 196; x += 10) {
      const double expected =
          o.width_px * (o.min_pressure + (1 - o.min_pressure) * pressure(style, x / 200.0, 200.0, 7, o));
      EXPECT_NEAR(coveredHeight(strip, x), expected, 0.4) << "at x = " << x;
    }
  }
  // The side tip runs the path along the heel: a fifth of the width on the right (y < 0).
  const std::vector<StripVertex> side = strokeStrip(path, StrokeStyle::Zhuye, 7, o);
  EXPECT_NEAR(side[0].position.y, -0.2 * o.width_px, 1e-9);
  EXPECT_NEAR(side[1].position.y, 0.8 * o.width_px, 1e-9);
}

TEST(Brush, PressureCurvesHaveTheirStylesShapes) {
  const BrushOptions o;
  // Zither string: even.
  for (double t = 0; t <= 1; t += 0.05) EXPECT_EQ(pressure(StrokeStyle::Qinxian, t, 100, 1, o), 1.0);
  // Willow leaf: 0 at both ends, 1 at a turn between 30 % and 70 %, seeded.
  std::set<double> peaks;
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    EXPECT_NEAR(pressure(StrokeStyle::Liuye, 0.0, 100, seed, o), 0.0, 1e-12);
    EXPECT_NEAR(pressure(StrokeStyle::Liuye, 1.0, 100, seed, o), 0.0, 1e-12);
    double best = 0, at = 0;
    for (double t = 0; t <= 1; t += 0.001) {
      const double p = pressure(StrokeStyle::Liuye, t, 100, seed, o);
      if (p > best) best = p, at = t;
    }
    EXPECT_NEAR(best, 1.0, 1e-4);
    EXPECT_GE(at, 0.299);
    EXPECT_LE(at, 0.701);
    peaks.insert(std::round(at * 100));
    EXPECT_EQ(pressure(StrokeStyle::Liuye, 0.4, 100, seed, o), pressure(StrokeStyle::Liuye, 0.4, 100, seed, o));
  }
  EXPECT_GE(peaks.size(), 4u) << "the turn varies with the seed";
  // Date pit: one quick 0 -> 1 -> 0 per beat of 30 px: 4 maxima on 120 px.
  int maxima = 0;
  double prev2 = -1, prev1 = -1;
  for (double t = 0; t <= 1.0001; t += 0.002) {
    const double p = pressure(StrokeStyle::Zaohe, t, 120, 1, o);
    if (prev1 > prev2 && prev1 >= p && prev1 > 0.99) ++maxima;
    prev2 = prev1;
    prev1 = p;
  }
  EXPECT_EQ(maxima, 4);
  // Reduced stroke and bamboo leaf: pressed at once, never pressed again.
  for (StrokeStyle style : {StrokeStyle::Jianbi, StrokeStyle::Zhuye}) {
    EXPECT_EQ(pressure(style, 0.0, 50, 1, o), 1.0);
    double last = 2;
    for (int i = 0; i <= 100; ++i) {
      const double p = pressure(style, i / 100.0, 50, 1, o);
      EXPECT_LE(p, last);
      last = p;
    }
    EXPECT_NEAR(last, 0.0, 1e-12);  // t = 1: lifted
  }
  // Mixed chooses by length.
  EXPECT_EQ(styleFor(StrokeStyle::Mixed, 200, o), StrokeStyle::Liuye);
  EXPECT_EQ(styleFor(StrokeStyle::Mixed, 60, o), StrokeStyle::Zaohe);
  EXPECT_EQ(styleFor(StrokeStyle::Mixed, 10, o), StrokeStyle::Jianbi);
  BrushOptions bad;
  bad.width_px = 0;
  test::expectErrorNaming([&] { strokeStrip({{0, 0}, {1, 0}}, StrokeStyle::Qinxian, 1, bad); }, "width", "0");
}

// Short strokes are left out: nothing under the length, full ink from three times it,
// rising without a step in between; a length of 0 keeps every stroke.
TEST(Brush, ShortStrokesFadeOutByLength) {
  EXPECT_EQ(lengthInk(0.0, 16.0), 0.0);
  EXPECT_EQ(lengthInk(16.0, 16.0), 0.0);
  EXPECT_EQ(lengthInk(48.0, 16.0), 1.0);
  EXPECT_EQ(lengthInk(1e9, 16.0), 1.0);
  EXPECT_NEAR(lengthInk(32.0, 16.0), 0.5, 1e-12);  // halfway, by symmetry of the smooth step
  double last = 0.0;
  for (double l = 16.0; l <= 48.0; l += 0.25) {
    const double k = lengthInk(l, 16.0);
    EXPECT_GE(k, last);
    EXPECT_LE(k - last, 0.02) << "no step at " << l;
    last = k;
  }
  for (double l : {0.0, 0.5, 100.0}) EXPECT_EQ(lengthInk(l, 0.0), 1.0);
  EXPECT_EQ(lengthInk(5.0, std::nan("")), 1.0);
}

}  // namespace
}  // namespace shanshui::strokes
