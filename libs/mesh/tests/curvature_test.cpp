// Object-space curvature against analytic surfaces: spheres of several radii (regular and
// jittered), a torus (K and H vary over it) and a paraboloid at its apex.
#include "shanshui/mesh/curvature.h"

#include <algorithm>
#include <numbers>
#include <random>

#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::mesh {
namespace {

double relativeMedianError(const std::vector<float>& got, const std::vector<double>& expected) {
  std::vector<double> e;
  for (std::size_t i = 0; i < got.size(); ++i)
    e.push_back(std::abs(got[i] - expected[i]) / std::max(std::abs(expected[i]), 1e-9));
  std::nth_element(e.begin(), e.begin() + static_cast<long>(e.size() / 2), e.end());
  return e[e.size() / 2];
}

TEST(Curvature, SpheresOfSeveralRadii) {
  for (double r : {0.01, 1.0, 250.0}) {
    const Mesh m = test::uvSphere(r, 48, 96);
    const VertexCurvature c = estimateCurvature(m);
    const std::vector<double> h(m.positions.size(), 1.0 / r), k(m.positions.size(), 1.0 / (r * r));
    EXPECT_LT(relativeMedianError(c.mean, h), 0.01) << "r = " << r;
    EXPECT_LT(relativeMedianError(c.gaussian, k), 0.01) << "r = " << r;
    EXPECT_LT(relativeMedianError(c.magnitude, h), 0.02) << "r = " << r;
    // Dimensionless: curvature times the feature size is the same for every radius.
    EXPECT_NEAR(curvatureFeatureSize(m, c) / r, 1.0, 0.05);
  }
}

TEST(Curvature, JitteredSphereStaysCloseOnAverage) {
  Mesh m = test::uvSphere(1.0, 40, 80);
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0.0, 1.0);
  for (glm::dvec3& p : m.positions) {
    // 15 % of the local edge length (shorter along the rings near the poles), then back
    // onto the sphere.
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - p.z * p.z));
    const double edge = std::min(std::numbers::pi / 40, 2 * std::numbers::pi * sinTheta / 80);
    p = glm::normalize(p + 0.15 * edge * glm::dvec3(jitter(rng), jitter(rng), jitter(rng)));
  }
  const VertexCurvature c = estimateCurvature(m);
  // The paper's screen-space estimate ranges over 0.12-210 on such a sphere (SPEC section 6);
  // the cotangent estimate is near 1 for most vertices (the skinny, jittered triangles at
  // the poles are the outliers).
  std::size_t close = 0;
  for (float h : c.mean) close += std::abs(h - 1.0f) < 0.3f;
  EXPECT_GT(close, c.mean.size() * 8 / 10);
  EXPECT_LT(relativeMedianError(c.mean, std::vector<double>(c.mean.size(), 1.0)), 0.15);
}

TEST(Curvature, TorusMatchesTheAnalyticCurvatures) {
  const double big = 3.0, small = 1.0;
  std::vector<double> cosV;
  const Mesh m = test::torus(big, small, 120, 60, &cosV);
  const VertexCurvature c = estimateCurvature(m);
  std::vector<double> k, h;
  for (double cv : cosV) {
    k.push_back(cv / (small * (big + small * cv)));
    h.push_back((big + 2 * small * cv) / (2 * small * (big + small * cv)));
  }
  // The mesh's triangles face inward-or-outward depending on winding; compare |H|.
  std::vector<float> absH(c.mean.size());
  for (std::size_t i = 0; i < absH.size(); ++i) absH[i] = std::abs(c.mean[i]);
  EXPECT_LT(relativeMedianError(absH, h), 0.02);
  double maxAbsK = 0.0;
  for (std::size_t i = 0; i < k.size(); ++i) maxAbsK = std::max(maxAbsK, std::abs(c.gaussian[i] - k[i]));
  EXPECT_LT(maxAbsK, 0.02);
}

TEST(Curvature, ParaboloidApexAndFlatPlane) {
  // z = (x² + y²) / 2: at the apex k1 = k2 = 1.
  const Mesh m = test::heightGrid(41, 41, 0.02, [](double x, double y) {
    const double u = x - 0.4, v = y - 0.4;
    return 0.5 * (u * u + v * v);
  });
  const VertexCurvature c = estimateCurvature(m);
  const std::size_t apex = 20 * 41 + 20;
  EXPECT_NEAR(std::abs(c.mean[apex]), 1.0, 0.01);
  EXPECT_NEAR(c.gaussian[apex], 1.0, 0.02);
  const Mesh flat = test::heightGrid(10, 10, 1.0, [](double, double) { return 0.0; });
  const VertexCurvature f = estimateCurvature(flat);
  for (std::size_t i = 0; i < f.mean.size(); ++i) {
    ASSERT_NEAR(f.mean[i], 0.0f, 1e-6f);
    ASSERT_NEAR(f.gaussian[i], 0.0f, 1e-6f);
  }
  EXPECT_EQ(curvatureFeatureSize(flat, f), 0.0);
  test::expectErrorNaming([&] { curvatureFeatureSize(flat, f, 100.0); }, "percentile", "100");
}

TEST(CurvatureFit, AgreesWithTheCotangentSignsAndTheAnalyticSphereAndTorus) {
  for (double r : {0.01, 1.0, 250.0}) {
    const Mesh m = test::uvSphere(r, 48, 96);
    const VertexCurvature fit = estimateCurvatureByFit(m), cot = estimateCurvature(m);
    const std::vector<double> h(m.positions.size(), 1.0 / r), k(m.positions.size(), 1.0 / (r * r));
    EXPECT_LT(relativeMedianError(fit.mean, h), 0.005) << "r = " << r;  // same sign convention
    EXPECT_LT(relativeMedianError(fit.gaussian, k), 0.01) << "r = " << r;
    EXPECT_LT(relativeMedianError(fit.magnitude, std::vector<double>(cot.magnitude.begin(), cot.magnitude.end())), 0.02)
        << "r = " << r;
  }
  const double big = 3.0, small = 1.0;
  std::vector<double> cosV;
  const Mesh t = test::torus(big, small, 120, 60, &cosV);
  const VertexCurvature c = estimateCurvatureByFit(t);
  double worst_k1 = 0, worst_k2 = 0;
  for (std::size_t i = 0; i < cosV.size(); ++i) {
    // |k1| = 1/r around the tube, |k2| = |cos v / (R + r cos v)| around the axis.
    const double around_axis = std::abs(cosV[i] / (big + small * cosV[i]));
    const double a = std::abs(c.k1[i]), b = std::abs(c.k2[i]);
    worst_k1 = std::max(worst_k1, std::abs(std::max(a, b) - 1.0 / small));
    worst_k2 = std::max(worst_k2, std::abs(std::min(a, b) - around_axis));
  }
  EXPECT_LT(worst_k1, 0.02);  // O(h²) with h = 2π/60 along the tube
  EXPECT_LT(worst_k2, 0.02);
}

TEST(CurvatureFit, StaysAccurateOnAJitteredSphereWhereCotangentsFail) {
  Mesh m = test::uvSphere(1.0, 40, 80);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.5, 0.5);
  for (glm::dvec3& p : m.positions) {
    // 30 % of an edge in every direction, back onto the sphere: many obtuse triangles.
    const double edge = std::numbers::pi / 40;
    p = glm::normalize(p + 0.6 * edge * glm::dvec3(jitter(rng), jitter(rng), jitter(rng)));
  }
  const VertexCurvature fit = estimateCurvatureByFit(m), cot = estimateCurvature(m);
  auto p90 = [](const std::vector<float>& v) {
    std::vector<double> e;
    for (float x : v) e.push_back(std::abs(x - 1.0));
    std::sort(e.begin(), e.end());
    return e[e.size() * 9 / 10];
  };
  EXPECT_LT(p90(fit.magnitude), 0.05);
  EXPECT_GT(p90(cot.magnitude), 0.5) << "the case is hard for cotangents (else the test proves nothing)";
}

TEST(CurvatureFit, FlatAndTinyMeshesFallBackWithoutNan) {
  const Mesh flat = test::heightGrid(10, 10, 1.0, [](double, double) { return 0.0; });
  for (float k : estimateCurvatureByFit(flat).magnitude) ASSERT_NEAR(k, 0.0f, 1e-6f);
  Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  for (float k : estimateCurvatureByFit(tri).magnitude) ASSERT_TRUE(std::isfinite(k));
}

// One-ring smoothing against what the mean of a vertex and its edge neighbours must do: a
// constant stays put, a linear field stays put at interior vertices of a regular grid (each
// neighbour has its mirror image), a spike spreads to its one ring and no further per sweep
// and keeps its sum where every vertex has the same valence, and zero sweeps change nothing.
TEST(SmoothOverOneRing, KeepsConstantsAndLinearFieldsAndSpreadsASpikeOneRingPerSweep) {
  const int n = 21;
  const Mesh grid = test::heightGrid(n, n, 1.0, [](double, double) { return 0.0; });
  std::vector<float> constant(grid.positions.size(), 2.5f);
  smoothOverOneRing(grid, constant, 5);
  for (float v : constant) EXPECT_FLOAT_EQ(v, 2.5f);

  std::vector<float> linear(grid.positions.size());
  for (std::size_t i = 0; i < linear.size(); ++i)
    linear[i] = static_cast<float>(3.0 * grid.positions[i].x - 2.0 * grid.positions[i].y);
  const std::vector<float> before = linear;
  smoothOverOneRing(grid, linear, 1);
  int interior = 0;
  for (int j = 1; j + 1 < n; ++j) {
    for (int i = 1; i + 1 < n; ++i) {
      const std::size_t v = static_cast<std::size_t>(j * n + i);
      EXPECT_NEAR(linear[v], before[v], 1e-4) << i << "," << j;
      ++interior;
    }
  }
  EXPECT_EQ(interior, (n - 2) * (n - 2));
  bool border_moved = false;
  for (std::size_t v = 0; v < linear.size(); ++v) border_moved = border_moved || std::abs(linear[v] - before[v]) > 1e-3;
  EXPECT_TRUE(border_moved) << "a corner has no mirror neighbours: the test can tell";

  std::vector<float> spike(grid.positions.size(), 0.0f);
  const std::size_t centre = static_cast<std::size_t>(10 * n + 10);
  spike[centre] = 7.0f;
  smoothOverOneRing(grid, spike, 1);
  int reached = 0;
  double sum = 0;
  for (std::size_t v = 0; v < spike.size(); ++v) {
    sum += spike[v];
    reached += spike[v] > 0.0f;
  }
  EXPECT_EQ(reached, 7) << "the vertex and its six edge neighbours";
  EXPECT_FLOAT_EQ(spike[centre], 1.0f);
  EXPECT_NEAR(sum, 7.0, 1e-5);

  std::vector<float> same = before;
  smoothOverOneRing(grid, same, 0);
  EXPECT_EQ(same, before);
}

}  // namespace
}  // namespace shanshui::mesh
