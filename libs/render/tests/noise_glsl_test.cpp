// The GLSL noises (shaders/common/noise_perlin.glsl, noise_gabor.glsl) against the CPU references
// in libs/noise, evaluated at the same points by a compute shader.
#include <algorithm>
#include <cmath>
#include <random>

#include "gl_probe.h"
#include "gl_test.h"
#include "shanshui/noise/gabor.h"
#include "shanshui/noise/perlin.h"
#include "shanshui/render/shader_program.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using NoiseGlsl = test::HeadlessGl;

// Runs shaders/common/noise_probe.comp over `points` (xyz) with kind 0 (Perlin) or 1 (Gabor).
std::vector<float> probe(const std::vector<glm::vec4>& points, int kind, const noise::GaborOptions& g = {}) {
  Program program({"noise_probe.comp"});
  program.set("u_kind", kind);
  program.set("u_gabor", glm::vec4(g.K, g.a, g.F0, g.omega0));
  program.set("u_gabor_misc", glm::vec2(g.isotropic ? 1.0f : 0.0f, static_cast<float>(g.impulses)));
  program.set("u_seed", noise::noiseSeed32(g.seed));
  return test::runProbe<float>(program, points);
}

TEST_F(NoiseGlsl, PerlinGivesThePublishedValuesInFloat) {
  const std::vector<glm::vec4> points{{3.14f, 42.0f, 7.0f, 0}, {-4.2f, 10.0f, 6.0f, 0}};
  const std::vector<float> v = probe(points, 0);
  EXPECT_NEAR(v[0], 0.13691995878400012, 2e-6);
  EXPECT_NEAR(v[1], 0.14208000000000043, 2e-6);
}

TEST_F(NoiseGlsl, PerlinMatchesTheCpuReferenceToFloatPrecision) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-300.0f, 300.0f);
  std::vector<glm::vec4> points(20000);
  for (auto& p : points) p = {u(rng), u(rng), u(rng), 0.0f};
  const std::vector<float> v = probe(points, 0);
  double worst = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double ref = noise::perlin(points[i].x, points[i].y, points[i].z);
    worst = std::max(worst, std::abs(ref - v[i]));
  }
  // Coordinates up to 300 in float carry 3e-5 of rounding into the lattice fractions;
  // the noise's gradient is below 3, so about 1e-4 at most.
  EXPECT_LT(worst, 2e-4);
}

TEST_F(NoiseGlsl, GaborMatchesTheCpuReferenceToFloatPrecision) {
  // Float positions can move a kernel across its 5 % truncation edge; such a point differs
  // by at most K · 0.05 · |w| ≤ 0.05 K. Everywhere else the difference is rounding.
  for (const bool isotropic : {false, true}) {
    noise::GaborOptions o;
    o.a = 0.08;
    o.F0 = 0.1;
    o.omega0 = 0.4;
    o.impulses = 40;
    o.isotropic = isotropic;
    o.seed = 0x1234567890ull;
    const noise::GaborNoise g(o);
    std::vector<glm::vec4> points;
    for (int y = -60; y < 60; ++y)
      for (int x = -60; x < 60; ++x) points.push_back({x * 1.37f, y * 1.41f, 0, 0});
    const std::vector<float> v = probe(points, 1, o);
    int rounding_only = 0;
    double worst = 0, mean = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d = std::abs(g(points[i].x, points[i].y) - v[i]);
      worst = std::max(worst, d);
      mean += d / static_cast<double>(points.size());
      if (d < 1e-4 * std::sqrt(g.variance()) * 10) ++rounding_only;
    }
    SCOPED_TRACE(isotropic ? "isotropic" : "anisotropic");
    EXPECT_LT(worst, 0.05 * o.K + 1e-3);
    EXPECT_LT(mean, 1e-4);
    EXPECT_GE(rounding_only, static_cast<int>(0.999 * static_cast<double>(points.size())));
  }
}

}  // namespace
}  // namespace shanshui::render
