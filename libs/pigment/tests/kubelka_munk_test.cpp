// Kubelka–Munk layers against what the model promises: a unit layer reproduces the two
// colours it was given, an empty layer is the substrate, layers of one pigment add their
// thicknesses, composition is associative, and every value stays finite and in [0, 1].
#include "shanshui/pigment/kubelka_munk.h"

#include <cmath>
#include <limits>
#include <random>

#include "shanshui/pigment/palette.h"
#include "test_support.h"

namespace shanshui::pigment {
namespace {

constexpr double kTol = 1e-12;

void expectNear(glm::dvec3 a, glm::dvec3 b, double tol) {
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], tol) << "channel " << i;
}

// Valid pigments: the palette's and random pairs with on_black < on_white, including
// near-black, near-white and nearly hiding ones.
std::vector<Pigment> pigments() {
  std::vector<Pigment> out;
  for (const NamedPigment& n : palette()) out.push_back(n.pigment);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(1e-3, 1.0 - 1e-3);
  for (int k = 0; k < 200; ++k) {
    Pigment p;
    for (int i = 0; i < 3; ++i) {
      const double x = u(rng), y = u(rng);
      p.on_white[i] = std::max(x, y);
      p.on_black[i] = std::min(x, y) * (x == y ? 0.5 : 1.0);
    }
    out.push_back(p);
  }
  out.push_back({{0.999, 0.999, 0.999}, {0.998, 0.5, 0.001}});
  return out;
}

TEST(KubelkaMunk, AUnitLayerReproducesItsColoursOnWhiteAndOnBlack) {
  for (const Pigment& p : pigments()) {
    const Layer l = layer(coefficients(p), 1.0);
    expectNear(onSubstrate(l, glm::dvec3(1.0)), p.on_white, 1e-9);
    expectNear(onSubstrate(l, glm::dvec3(0.0)), p.on_black, 1e-9);
  }
}

TEST(KubelkaMunk, AnEmptyLayerIsTheSubstrate) {
  const Layer l = layer(coefficients(named("ochre")), 0.0);
  expectNear(l.R, glm::dvec3(0.0), kTol);
  expectNear(l.T, glm::dvec3(1.0), kTol);
  for (const glm::dvec3 g : {glm::dvec3(0.0), glm::dvec3(1.0), glm::dvec3(0.2, 0.7, 0.9)})
    expectNear(onSubstrate(l, g), g, kTol);
}

// Two layers of one pigment are one layer of the summed thickness: the model's own
// consistency, independent of how the formulas were derived.
TEST(KubelkaMunk, LayersOfOnePigmentAddTheirThicknesses) {
  for (const Pigment& p : pigments()) {
    const Coefficients c = coefficients(p);
    for (const auto& [t1, t2] : {std::pair{0.3, 0.7}, std::pair{0.05, 2.0}, std::pair{1.5, 1.5}}) {
      const Layer a = over(layer(c, t1), layer(c, t2)), b = layer(c, t1 + t2);
      expectNear(a.R, b.R, 1e-9);
      expectNear(a.T, b.T, 1e-9);
    }
  }
}

TEST(KubelkaMunk, CompositionIsAssociative) {
  const auto& pal = palette();
  for (std::size_t i = 0; i + 2 < pal.size(); ++i) {
    const Layer a = layer(coefficients(pal[i].pigment), 0.4), b = layer(coefficients(pal[i + 1].pigment), 1.3),
                c = layer(coefficients(pal[i + 2].pigment), 0.8);
    const Layer left = over(over(a, b), c), right = over(a, over(b, c));
    expectNear(left.R, right.R, kTol);
    expectNear(left.R_below, right.R_below, kTol);
    expectNear(left.T, right.T, kTol);
    // And on a substrate, as the pigment pass uses it.
    expectNear(onSubstrate(over(a, b), glm::dvec3(0.9)), onSubstrate(a, onSubstrate(b, glm::dvec3(0.9))), kTol);
  }
}

// A thicker layer hides more of the substrate: darker on white, brighter on black, both
// tending to the pigment's R∞ = a − b; finite and in [0, 1] at any thickness.
TEST(KubelkaMunk, ThicknessHidesTheSubstrateAndStaysFiniteAtExtremes) {
  for (const Pigment& p : pigments()) {
    const Coefficients c = coefficients(p);
    glm::dvec3 lastWhite(2.0), lastBlack(-1.0);
    for (double t : {0.0, 1e-300, 1e-9, 0.1, 1.0, 10.0, 1e3, 1e9, 1e300, std::numeric_limits<double>::max()}) {
      const Layer l = layer(c, t);
      const glm::dvec3 w = onSubstrate(l, glm::dvec3(1.0)), k = onSubstrate(l, glm::dvec3(0.0));
      for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(std::isfinite(l.R[i]) && std::isfinite(l.T[i])) << "t = " << t;
        EXPECT_GE(l.R[i], 0.0);
        EXPECT_LE(l.R[i] + l.T[i], 1.0 + 1e-12) << "energy at t = " << t;
        EXPECT_LE(w[i], lastWhite[i] + 1e-12);
        EXPECT_GE(k[i], lastBlack[i] - 1e-12);
      }
      lastWhite = w;
      lastBlack = k;
    }
    const Layer thick = layer(c, 1e300);
    expectNear(thick.R, c.a - c.b, 1e-12);
    expectNear(thick.T, glm::dvec3(0.0), 1e-12);
  }
}

TEST(KubelkaMunk, InvalidPigmentsAreRefusedByChannel) {
  test::expectErrorNaming(
      [] {
        coefficients({{0.5, 0.5, 0.5}, {0.5, 0.1, 0.1}}, "objects.0.pigment");
      },
      "objects.0.pigment", "red on black 0.5 is not darker");
  test::expectErrorNaming([] { coefficients({{0.5, 1.0, 0.5}, {0.1, 0.1, 0.1}}, "p"); }, "p", "green on white 1");
  test::expectErrorNaming([] { coefficients({{0.5, 0.5, 0.5}, {0.1, 0.1, 0.0}}, "p"); }, "p", "blue");
  test::expectErrorNaming([] { coefficients({{0.5, 0.5, std::nan("")}, {0.1, 0.1, 0.1}}, "p"); }, "p", "blue");
  test::expectErrorNaming([] { named("vermilion"); }, "vermilion", "ochre, indigo");
}

}  // namespace
}  // namespace shanshui::pigment
