// The CPU reference of the ink diffusion against its invariants (SPEC.md section 9):
// conservation, no negative ink or NaN on a grid of extreme parameters, symmetry, the
// ring structure, and the distance transform against the plain iteration.
#include "shanshui/ink/diffusion.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "test_support.h"

namespace shanshui::ink {
namespace {

InkField randomStrokes(int w, int h, unsigned seed, double density = 0.05, bool uniform = false) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  InkField f{w, h, std::vector<double>(static_cast<std::size_t>(w) * h, 0.0)};
  for (double& v : f.ink) {
    const double r = u(rng);
    if (r < density)
      v = uniform ? 0.9 : 0.55 + 0.45 * u(rng);  // strokes
    else if (r < 3 * density)
      v = 0.3 * u(rng);  // light wash, below the threshold
  }
  return f;
}

InkField rotate90(const InkField& f) {  // clockwise
  InkField r{f.height, f.width, std::vector<double>(f.ink.size())};
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) r.ink[static_cast<std::size_t>(x) * r.width + (f.height - 1 - y)] = f.at(x, y);
  return r;
}

InkField flipX(const InkField& f) {
  InkField r = f;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) r.ink[static_cast<std::size_t>(y) * f.width + (f.width - 1 - x)] = f.at(x, y);
  return r;
}

double maxDifference(const InkField& a, const InkField& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.ink.size(); ++i) m = std::max(m, std::abs(a.ink[i] - b.ink[i]));
  return m;
}

std::vector<bool> strokes(const InkField& f, double threshold) {
  std::vector<bool> s(f.ink.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = f.ink[i] > threshold;
  return s;
}

TEST(Diffusion, OptionsOutOfRangeAreRefusedByName) {
  DiffusionOptions o;
  o.ring_steps = 300;
  test::expectErrorNaming([&] { validate(o); }, "ring_steps", "300");
  o = {};
  o.attenuation = 1.5;
  test::expectErrorNaming([&] { validate(o); }, "attenuation", "1.5");
  o = {};
  o.iterations = -1;
  test::expectErrorNaming([&] { validate(o); }, "iterations", "-1");
  o = {};
  o.residual = std::nan("");
  EXPECT_THROW(validate(o), Error);
}

TEST(Diffusion, DistanceTransformGivesTheRingsOfTheIteration) {
  for (unsigned seed : {1u, 2u, 3u}) {
    for (int d : {0, 1, 5, 64}) {
      SCOPED_TRACE(std::to_string(seed) + " d=" + std::to_string(d));
      DiffusionOptions o;
      o.ring_steps = d;
      o.attenuation = 0.8;
      const InkField in = randomStrokes(61, 47, seed, 0.01);
      std::vector<int> ring_iter, ring_dt;
      const InkField a = mainDiffusionIterative(in, o, &ring_iter), b = mainDiffusionDistance(in, o, &ring_dt);
      EXPECT_EQ(ring_iter, ring_dt);
      // The ink differs at most by f^r times the spread of the stroke ink that reaches a
      // pixel; with strokes of one ink the two are equal.
      double spread = 0, lo = 1, hi = 0;
      for (std::size_t i = 0; i < in.ink.size(); ++i)
        if (ring_iter[i] == 0) lo = std::min(lo, in.ink[i]), hi = std::max(hi, in.ink[i]);
      spread = hi - lo;
      for (std::size_t i = 0; i < in.ink.size(); ++i) {
        if (ring_iter[i] <= 0) continue;
        ASSERT_LE(std::abs(a.ink[i] - b.ink[i]), std::pow(o.attenuation, ring_iter[i]) * spread + 1e-12) << i;
      }
      const InkField uniform = randomStrokes(61, 47, seed, 0.01, true);
      EXPECT_LT(maxDifference(mainDiffusionIterative(uniform, o), mainDiffusionDistance(uniform, o)), 1e-12);
    }
  }
}

TEST(Diffusion, OpacityDecaysGeometricallyAndNeverIncreasesWithTheRing) {
  InkField in{41, 41, std::vector<double>(41 * 41, 0.0)};
  in.ink[20 * 41 + 20] = 1.0;  // one stroke pixel
  DiffusionOptions o;
  o.ring_steps = 15;
  o.attenuation = 0.7;
  std::vector<int> ring;
  const InkField out = mainDiffusionIterative(in, o, &ring);
  for (int y = 0; y < 41; ++y)
    for (int x = 0; x < 41; ++x) {
      const int r = std::abs(x - 20) + std::abs(y - 20);
      const std::size_t i = static_cast<std::size_t>(y) * 41 + x;
      EXPECT_EQ(ring[i], r <= 15 ? r : -1);
      EXPECT_NEAR(out.ink[i], r <= 15 ? std::pow(0.7, r) : 0.0, 1e-12);
    }
}

TEST(Diffusion, BoundaryDiffusionConservesInkAndRespectsTheResidual) {
  for (unsigned seed : {4u, 5u}) {
    for (double absorb : {0.2, 1000.0}) {
      SCOPED_TRACE(std::to_string(seed) + " absorb " + std::to_string(absorb));
      DiffusionOptions o;
      o.absorb = absorb;
      o.residual = 0.1;
      o.iterations = 7;
      const InkField in = randomStrokes(53, 38, seed, 0.08);
      const InkField out = boundaryDiffusion(in, {}, strokes(in, o.threshold), o);
      EXPECT_NEAR(out.total(), in.total(), 1e-9 * in.total());
      for (std::size_t i = 0; i < in.ink.size(); ++i) {
        ASSERT_TRUE(std::isfinite(out.ink[i]));
        // Nobody is pushed below the residual (or below what it had, if it had less).
        ASSERT_GE(out.ink[i], std::min(in.ink[i], o.residual) - 1e-12) << i;
      }
      EXPECT_GT(maxDifference(in, out), 0.01) << "ink moved";
    }
  }
}

TEST(Diffusion, NothingFlowsWithoutInkAboveTheResidual) {
  DiffusionOptions o;
  o.residual = 0.4;
  o.threshold = 0.9;
  InkField in = randomStrokes(30, 20, 6, 0.0);  // light wash only, all below 0.3
  const InkField out = boundaryDiffusion(in, {}, strokes(in, o.threshold), o);
  EXPECT_EQ(out.ink, in.ink);
}

TEST(Diffusion, AbsorbencyGatesTheFlow) {
  DiffusionOptions o;
  o.ring_steps = 0;
  const InkField in = randomStrokes(40, 40, 7, 0.1);
  const std::vector<float> none(in.ink.size(), 0.0f), half(in.ink.size(), 0.5f);
  EXPECT_EQ(diffuseInk(in, none, o).ink, in.ink) << "paper that absorbs nothing";
  const double moved_half = maxDifference(in, diffuseInk(in, half, o)),
               moved_full = maxDifference(in, diffuseInk(in, {}, o));
  EXPECT_GT(moved_half, 0.0);
  EXPECT_GT(moved_full, moved_half);
}

TEST(Diffusion, ResultTurnsAndMirrorsWithTheImage) {
  DiffusionOptions o;
  o.ring_steps = 6;
  o.iterations = 4;
  o.absorb = 0.8;
  const InkField in = randomStrokes(37, 29, 8, 0.03, true);
  const InkField out = diffuseInk(in, {}, o);
  EXPECT_LT(maxDifference(diffuseInk(rotate90(in), {}, o), rotate90(out)), 1e-12);
  EXPECT_LT(maxDifference(diffuseInk(flipX(in), {}, o), flipX(out)), 1e-12);
}

TEST(Diffusion, ExtremeParametersAndImagesStayFiniteNonNegativeAndConserved) {
  std::vector<InkField> images;
  images.push_back(randomStrokes(33, 21, 9));
  images.push_back({16, 16, std::vector<double>(256, 0.0)});  // empty
  images.push_back({16, 16, std::vector<double>(256, 1.0)});  // full
  images.push_back({1, 1, {1.0}});
  images.push_back({1, 1, {0.0}});
  InkField border{24, 12, std::vector<double>(24 * 12, 0.0)};  // strokes on every edge
  for (int x = 0; x < 24; ++x) border.ink[x] = border.ink[11 * 24 + x] = 1.0;
  for (int y = 0; y < 12; ++y) border.ink[y * 24] = border.ink[y * 24 + 23] = 0.8;
  images.push_back(border);
  int cases = 0;
  for (const InkField& in : images)
    for (int n : {1, 100})
      for (double ir : {0.0, 1.0})
        for (double f : {0.0, 1.0})
          for (int d : {0, 64})
            for (double ip : {0.5, 1000.0}) {
              DiffusionOptions o;
              o.iterations = n;
              o.residual = ir;
              o.attenuation = f;
              o.ring_steps = d;
              o.absorb = ip;
              const InkField main = mainDiffusionDistance(in, o);
              const InkField out = boundaryDiffusion(main, {}, strokes(in, o.threshold), o);
              for (double v : out.ink)
                ASSERT_TRUE(std::isfinite(v) && v >= 0.0) << v << " n=" << n << " ir=" << ir << " f=" << f << " d=" << d
                                                          << " ip=" << ip << " image " << in.width << "x" << in.height;
              ASSERT_NEAR(out.total(), main.total(), 1e-9 * std::max(main.total(), 1.0));
              std::vector<int> a, b;
              mainDiffusionIterative(in, o, &a);
              mainDiffusionDistance(in, o, &b);
              ASSERT_EQ(a, b);
              ++cases;
            }
  EXPECT_EQ(cases, 6 * 32);
}

TEST(Diffusion, RealScansKeepTheInvariants) {
  const auto scans = test::textureScans();
  const double paper[3] = {1.0, 1.0, 1.0};
  int tested = 0;
  for (const auto& path : scans) {
    SCOPED_TRACE(path.string());
    image::Image img = image::loadImage(path);
    if (img.channels < 3) {
      image::Image rgb(img.width, img.height, 3);
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          for (int ch = 0; ch < 3; ++ch) rgb.at(x, y, ch) = img.at(x, y, 0);
      img = rgb;
    }
    const InkField in = inkFromImage(img, paper);
    DiffusionOptions o;
    o.iterations = 10;
    o.ring_steps = 6;
    const InkField main = mainDiffusionDistance(in, o);
    const InkField out = boundaryDiffusion(main, {}, strokes(in, o.threshold), o);
    for (double v : out.ink) ASSERT_TRUE(std::isfinite(v) && v >= 0.0);
    EXPECT_NEAR(out.total(), main.total(), 1e-9 * std::max(main.total(), 1.0));
    std::vector<int> a, b;
    mainDiffusionIterative(in, o, &a);
    mainDiffusionDistance(in, o, &b);
    EXPECT_EQ(a, b);
    EXPECT_LT(maxDifference(diffuseInk(flipX(in), {}, o), flipX(diffuseInk(in, {}, o))), 1e-12);
    ++tested;
  }
  EXPECT_GT(tested, 0);
}

TEST(Diffusion, PictureRoundTripChangesOnlyWhereInkChanged) {
  image::Image rgb(8, 4, 3, 0.0f);
  const double paper[3] = {0.95, 0.93, 0.87};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = static_cast<float>(paper[c] * (x < 2 ? 0.1 : 1.0));
  const InkField before = inkFromImage(rgb, paper);
  EXPECT_NEAR(before.at(0, 0), 0.9, 1e-6);
  EXPECT_NEAR(before.at(5, 0), 0.0, 1e-6);
  InkField after = before;
  after.ink[3] += 0.25;  // (3, 0)
  const image::Image out = applyInk(rgb, before, after, paper);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x)
      for (int c = 0; c < 3; ++c) {
        const float expected =
            (x == 3 && y == 0) ? static_cast<float>(rgb.at(x, y, c) - 0.25 * paper[c]) : rgb.at(x, y, c);
        EXPECT_FLOAT_EQ(out.at(x, y, c), expected);
      }
}

}  // namespace
}  // namespace shanshui::ink
