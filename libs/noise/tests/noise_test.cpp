// Perlin against the published values; Gabor noise against its analytic variance and
// orientation statistics, and on extreme parameters.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <opencv2/core.hpp>

#include "shanshui/core/error.h"
#include "shanshui/noise/canvas.h"
#include "shanshui/noise/gabor.h"
#include "shanshui/noise/perlin.h"
#include "shanshui/noise/value_noise.h"
#include "test_support.h"

namespace shanshui::noise {
namespace {

TEST(Perlin, PublishedValuesBitExact) {
  EXPECT_EQ(perlin(3.14, 42, 7), 0.13691995878400012);
  EXPECT_EQ(perlin(-4.2, 10, 6), 0.14208000000000043);
}

TEST(Perlin, ZeroOnTheLatticeBoundedAndPeriodic) {
  double lo = 0, hi = 0;
  for (int i = 0; i < 20000; ++i) {
    const double x = 0.37 * i, y = 0.11 * i - 40, z = 0.053 * i;
    const double v = perlin(x, y, z);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    ASSERT_NEAR(v, perlin(x + 256, y - 512, z + 256), 1e-12);
  }
  EXPECT_GE(lo, -1.0);
  EXPECT_LE(hi, 1.0);
  EXPECT_LT(lo, -0.5);
  EXPECT_GT(hi, 0.5);
  for (int i = -3; i < 3; ++i) EXPECT_EQ(perlin(i, 2 * i, -i), 0.0);
  EXPECT_EQ(perlinFade(0.0), 0.0);
  EXPECT_EQ(perlinFade(1.0), 1.0);
  EXPECT_EQ(perlinFade(0.5), 0.5);
}

// Samples of one image of the noise on a unit grid.
std::vector<double> sampleImage(const GaborNoise& g, int size, double offset) {
  std::vector<double> v;
  v.reserve(static_cast<std::size_t>(size) * size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) v.push_back(g(offset + x, offset + y));
  return v;
}

TEST(Gabor, VarianceWithinThreePercentOfTheAnalyticValue) {
  for (bool isotropic : {false, true}) {
    SCOPED_TRACE(isotropic ? "isotropic" : "anisotropic");
    double sum = 0, sum2 = 0;
    std::size_t n = 0;
    double expected = 0;
    for (std::uint64_t seed = 1; seed <= 32; ++seed) {
      GaborOptions o;
      o.a = 0.1;
      o.F0 = 0.08;
      o.impulses = 32;
      o.isotropic = isotropic;
      o.seed = seed;
      const GaborNoise g(o);
      expected = g.variance();
      for (double v : sampleImage(g, 160, 1000.0 * static_cast<double>(seed))) sum += v, sum2 += v * v, ++n;
    }
    const double mean = sum / static_cast<double>(n), var = sum2 / static_cast<double>(n) - mean * mean;
    EXPECT_NEAR(var / expected, 1.0, 0.03) << var << " vs " << expected;
    EXPECT_NEAR(mean, 0.0, 0.05 * std::sqrt(expected));
  }
}

// Coherence of the structure tensor averaged over `images` images of the noise: 1 for one
// orientation, 0 for none.
double orientationCoherence(GaborOptions o, int size, int images) {
  double jxx = 0, jyy = 0, jxy = 0;
  for (int k = 0; k < images; ++k) {
    o.seed = static_cast<std::uint64_t>(k) + 1;
    const GaborNoise g(o);
    for (int y = 1; y + 1 < size; ++y)
      for (int x = 1; x + 1 < size; ++x) {
        const double gx = 0.5 * (g(x + 1, y) - g(x - 1, y)), gy = 0.5 * (g(x, y + 1) - g(x, y - 1));
        jxx += gx * gx, jyy += gy * gy, jxy += gx * gy;
      }
  }
  return std::sqrt((jxx - jyy) * (jxx - jyy) + 4 * jxy * jxy) / (jxx + jyy);
}

TEST(Gabor, AnisotropicNoiseIsOrientedAndIsotropicIsNot) {
  GaborOptions o;
  o.a = 0.05;
  o.F0 = 0.1;
  o.impulses = 32;
  EXPECT_GT(orientationCoherence(o, 128, 8), 0.8);
  o.isotropic = true;
  EXPECT_LT(orientationCoherence(o, 128, 8), 0.02);
}

TEST(Gabor, AveragedPowerSpectrumMatchesTheAnalyticOne) {
  // The periodogram |DFT(w·noise)|² / Σw² of unit-spaced samples estimates the spectral
  // density; a Hann window w keeps the image's edges from leaking power out of the peak,
  // and the spectrum is far below Nyquist, so aliasing is negligible. A periodogram bin
  // fluctuates by its own mean: 64 images keep that near 0.13.
  const int n = 128, images = 64;
  GaborOptions o;
  o.a = 0.06;
  o.F0 = 0.12;
  o.omega0 = 0.6;
  o.impulses = 32;
  cv::Mat average = cv::Mat::zeros(n, n, CV_64F);
  std::vector<double> hann(n);
  double window_energy = 0;
  for (int i = 0; i < n; ++i) hann[i] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * (i + 0.5) / n);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) window_energy += hann[x] * hann[x] * hann[y] * hann[y];
  GaborNoise g(o);
  for (int k = 0; k < images; ++k) {
    o.seed = static_cast<std::uint64_t>(k) + 11;
    g = GaborNoise(o);
    cv::Mat img(n, n, CV_64F);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) img.at<double>(y, x) = hann[x] * hann[y] * g(x, y);
    cv::Mat spectrum;
    cv::dft(img, spectrum, cv::DFT_COMPLEX_OUTPUT);
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const cv::Vec2d c = spectrum.at<cv::Vec2d>(y, x);
        average.at<double>(y, x) += (c[0] * c[0] + c[1] * c[1]) / (window_energy * images);
      }
  }
  double peak = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double fx = (x < n / 2 ? x : x - n) / static_cast<double>(n),
                   fy = (y < n / 2 ? y : y - n) / static_cast<double>(n);
      peak = std::max(peak, g.spectrum(fx, fy));
    }
  double err2 = 0, ref2 = 0;
  int bins = 0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double fx = (x < n / 2 ? x : x - n) / static_cast<double>(n),
                   fy = (y < n / 2 ? y : y - n) / static_cast<double>(n);
      const double s = g.spectrum(fx, fy);
      if (s < 0.01 * peak) continue;
      err2 += (average.at<double>(y, x) - s) * (average.at<double>(y, x) - s);
      ref2 += s * s;
      ++bins;
    }
  EXPECT_GT(bins, 100);
  EXPECT_LT(std::sqrt(err2 / ref2), 0.2);
}

TEST(Gabor, SameSeedSameNoiseAnywhereAndAnyOrder) {
  GaborOptions o;
  const GaborNoise a(o), b(o);
  EXPECT_EQ(a(123.25, -77.5), b(123.25, -77.5));
  const double first = a(5e6, -3e6);
  a(0, 0);
  EXPECT_EQ(a(5e6, -3e6), first);
  o.seed = 2;
  EXPECT_NE(GaborNoise(o)(123.25, -77.5), a(123.25, -77.5));
}

TEST(Gabor, ExtremeParametersGiveFiniteValuesQuickly) {
  for (double impulses : {1.0, 1024.0})
    for (double a : {1e-3, 1e2})
      for (double f0 : {0.0, 0.5}) {
        GaborOptions o;
        o.impulses = impulses;
        o.a = a;
        o.F0 = f0;
        const GaborNoise g(o);
        for (int i = 0; i < 50; ++i) ASSERT_TRUE(std::isfinite(g(i * 17.3, i * -4.1)));
        ASSERT_TRUE(std::isfinite(g.variance()) && g.variance() > 0);
      }
  GaborOptions bad;
  bad.impulses = 0;
  test::expectErrorNaming([&] { validate(bad); }, "impulses", "0");
  bad = {};
  bad.a = -1;
  test::expectErrorNaming([&] { validate(bad); }, "gabor.a", "-1");
}

}  // namespace
}  // namespace shanshui::noise

namespace shanshui::noise {
namespace {

// A brute-force canvas: impulses scattered uniformly (exact mean count) over the image and
// a margin of one radius, each adding w · canvasKernel; the sample variance over many
// images against canvasSigma()².
double simulatedCanvasVariance(const CanvasNoiseOptions& o, int images) {
  const int n = 96;
  const double r = o.radius, lo = -r, hi = n + r;
  const double density = o.impulses / (std::numbers::pi * r * r);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double sum = 0, sum2 = 0;
  std::size_t count = 0;
  for (int k = 0; k < images; ++k) {
    std::vector<double> img(static_cast<std::size_t>(n) * n, 0.0);
    const int impulses = impulseCount(density * (hi - lo) * (hi - lo), u(rng));
    for (int i = 0; i < impulses; ++i) {
      const double px = lo + (hi - lo) * u(rng), py = lo + (hi - lo) * u(rng), w = 2 * u(rng) - 1;
      const double e0 = u(rng), e1 = u(rng), e2 = u(rng);
      for (int y = std::max(0, static_cast<int>(py - r)); y <= std::min(n - 1, static_cast<int>(py + r)); ++y)
        for (int x = std::max(0, static_cast<int>(px - r)); x <= std::min(n - 1, static_cast<int>(px + r)); ++x)
          img[static_cast<std::size_t>(y) * n + x] += w * canvasKernel(o, x - px, y - py, e0, e1, e2);
    }
    for (double v : img) {
      sum += v;
      sum2 += v * v;
      ++count;
    }
  }
  const double mean = sum / static_cast<double>(count);
  return sum2 / static_cast<double>(count) - mean * mean;
}

TEST(Canvas, SigmaMatchesABruteForceCanvasForEveryPattern) {
  CanvasNoiseOptions silk;
  silk.silk = true;
  silk.impulses = 24;
  CanvasNoiseOptions felt = silk;
  felt.isotropic = true;
  felt.omega0 = 1.0;
  CanvasNoiseOptions rice;
  rice.impulses = 24;
  CanvasNoiseOptions one_way = silk;
  one_way.mix = 0.0;
  one_way.omega0 = 0.7;
  for (const auto& [name, o] : {std::pair{"silk", silk}, {"felt", felt}, {"rice paper", rice}, {"one way", one_way}}) {
    SCOPED_TRACE(name);
    const double sigma = canvasSigma(o);
    EXPECT_NEAR(simulatedCanvasVariance(o, 48) / (sigma * sigma), 1.0, 0.03);
  }
}

TEST(Canvas, PerlinMeanSquareIsStable) {
  // The constant behind the rice paper's normalisation, against an independent estimate
  // (a plain pseudo-random sample).
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 256.0);
  double sum = 0;
  const int n = 400000;
  for (int i = 0; i < n; ++i) {
    const double v = perlin(u(rng), u(rng), u(rng));
    sum += v * v;
  }
  EXPECT_NEAR(perlinMeanSquare() / (sum / n), 1.0, 0.01);
  EXPECT_GT(perlinMeanSquare(), 0.01);
}

TEST(ErosionNoise, SeededTileableAndSpanningTheUnitRange) {
  const image::Image a = erosionNoise(64, 7), b = erosionNoise(64, 7), c = erosionNoise(64, 8);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_NE(a.pixels, c.pixels);
  for (int ch = 0; ch < 2; ++ch) {
    float lo = 1, hi = 0, step = 0, wrap = 0;
    for (int y = 0; y < 64; ++y) {
      for (int x = 0; x < 64; ++x) {
        lo = std::min(lo, a.at(x, y, ch));
        hi = std::max(hi, a.at(x, y, ch));
        if (x > 0) step = std::max(step, std::abs(a.at(x, y, ch) - a.at(x - 1, y, ch)));
      }
      wrap = std::max(wrap, std::abs(a.at(0, y, ch) - a.at(63, y, ch)));
    }
    EXPECT_EQ(lo, 0.0f);
    EXPECT_EQ(hi, 1.0f);
    EXPECT_LE(wrap, step * 1.01f) << "the seam across the tile edge is no larger than any step inside";
  }
}

TEST(ErosionNoise, TheCoarseChannelAloneIsTheFirstChannel) {
  const image::Image both = erosionNoise(96, 5), coarse = erosionNoiseCoarse(96, 5);
  ASSERT_EQ(coarse.channels, 1);
  ASSERT_EQ(coarse.width, 96);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) ASSERT_EQ(coarse.at(x, y, 0), both.at(x, y, 0)) << x << "," << y;
}

}  // namespace
}  // namespace shanshui::noise
