// Image quilting (SPEC.md section 3): the FFT overlap search against the exhaustive one,
// invariants of the output on every sample texture, determinism across thread counts,
// tileability, and the metrics on outputs with known answers.
#include "shanshui/texsynth/quilting.h"

#include <algorithm>
#include <random>

#include "shanshui/image/image_io.h"
#include "shanshui/texsynth/quilt_metrics.h"
#include "test_support.h"

namespace shanshui::texsynth {
namespace {

namespace fs = std::filesystem;

cv::Mat maskOf(int b, int left, int top, int right, int bottom) {
  cv::Mat m = cv::Mat::zeros(b, b, CV_8U);
  if (left) m.colRange(0, left).setTo(1);
  if (top) m.rowRange(0, top).setTo(1);
  if (right) m.colRange(b - right, b).setTo(1);
  if (bottom) m.rowRange(b - bottom, b).setTo(1);
  return m;
}

// A plausible "already synthesised" footprint: a window of the sample plus a little noise.
image::Image footprint(const image::Image& sample, int b, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0.0f, 0.02f);
  const int x0 = static_cast<int>(rng() % (sample.width - b + 1)),
            y0 = static_cast<int>(rng() % (sample.height - b + 1));
  image::Image p(b, b, sample.channels);
  for (int y = 0; y < b; ++y)
    for (int x = 0; x < b; ++x)
      for (int c = 0; c < sample.channels; ++c) p.at(x, y, c) = sample.at(x0 + x, y0 + y, c) + n(rng);
  return p;
}

std::vector<int> candidateSet(const cv::Mat& e, long long values) {
  double lo = 0;
  cv::minMaxLoc(e, &lo);
  const double threshold = candidateThreshold(lo, values, QuiltOptions{});
  std::vector<int> set;
  for (int i = 0; i < e.rows * e.cols; ++i)
    if (e.at<double>(i / e.cols, i % e.cols) <= threshold) set.push_back(i);
  return set;
}

TEST(OverlapSearch, FftEqualsExhaustiveOnEveryTextureAndMaskShape) {
  const auto files = test::textureScans();
  const int b = 24;
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    const image::Image sample = image::loadImage(f);
    const OverlapSearch search(sample, b);
    const cv::Mat masks[] = {maskOf(b, 4, 0, 0, 0), maskOf(b, 4, 4, 0, 0), maskOf(b, 5, 3, 6, 2),
                             maskOf(b, 0, 0, 0, 1)};
    unsigned seed = 1;
    for (const cv::Mat& mask : masks) {
      const image::Image patch = footprint(sample, b, seed++);
      const cv::Mat fft = search.errors(patch, mask, SearchMode::Fft);
      const cv::Mat exact = search.errors(patch, mask, SearchMode::Exhaustive);
      ASSERT_EQ(fft.size(), exact.size());
      double maxExact = 0;
      cv::minMaxLoc(exact, nullptr, &maxExact);
      EXPECT_LE(cv::norm(fft, exact, cv::NORM_INF), 1e-9 * (1 + maxExact));
      // Spot-check the exhaustive map itself against the direct single-window sum.
      EXPECT_DOUBLE_EQ(exact.at<double>(3, 5), search.errorAt(patch, mask, 5, 3));
      const long long values = static_cast<long long>(cv::countNonZero(mask)) * sample.channels;
      EXPECT_EQ(candidateSet(fft, values), candidateSet(exact, values));
    }
  }
}

TEST(OverlapSearch, ZeroErrorWhereThePatchIsCopiedFromTheSample) {
  std::mt19937 rng(5);
  image::Image sample(40, 30, 3);
  for (float& v : sample.pixels) v = static_cast<float>(rng() % 1000) / 999.0f;
  const int b = 9;
  const OverlapSearch search(sample, b);
  image::Image patch(b, b, 3);
  for (int y = 0; y < b; ++y)
    for (int x = 0; x < b; ++x)
      for (int c = 0; c < 3; ++c) patch.at(x, y, c) = sample.at(17 + x, 11 + y, c);
  const cv::Mat e = search.errors(patch, maskOf(b, 3, 3, 0, 0), SearchMode::Fft);
  cv::Point at;
  double lo = 1;
  cv::minMaxLoc(e, &lo, nullptr, &at);
  EXPECT_EQ(at, cv::Point(17, 11));
  EXPECT_LT(lo, 1e-9);
}

struct Measured {
  QuiltResult result;
  QuiltMetrics metrics;
};

Measured synthesise(const image::Image& sample, QuiltOptions o) {
  Measured r{quilt(sample, o), {}};
  QuiltMetricsOptions m;
  m.patches = 64;
  r.metrics = measureQuilt(sample, r.result, o.block, m);
  return r;
}

void expectEveryPixelFromTheSample(const image::Image& sample, const QuiltResult& r) {
  const image::Image& out = r.image;
  ASSERT_EQ(r.source.size(), static_cast<std::size_t>(out.width) * out.height);
  for (int y = 0; y < out.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const int s = r.source[static_cast<std::size_t>(y) * out.width + x];
      ASSERT_GE(s, 0);
      ASSERT_LT(s, sample.width * sample.height);
      for (int c = 0; c < out.channels; ++c) {
        ASSERT_EQ(out.at(x, y, c), sample.pixels[static_cast<std::size_t>(s) * sample.channels + c])
            << "pixel " << x << "," << y;
      }
    }
  }
}

TEST(Quilt, EveryTextureEverySeamGivesPixelsFromTheSampleAndBeatsRandomPlacement) {
  const auto files = test::textureScans();
  for (const fs::path& f : files) {
    const image::Image sample = image::loadImage(f);
    QuiltOptions o;
    o.width = 150;
    o.height = 110;
    o.block = std::min({32, sample.width, sample.height});
    o.seed = 3;
    QuiltOptions random = o;
    random.search = SearchMode::Random;
    const Measured baseline = synthesise(sample, random);
    for (SeamMode seam : {SeamMode::Cut, SeamMode::GraphCut, SeamMode::None}) {
      SCOPED_TRACE(f.filename().string() + " seam " + seamModeName(seam));
      o.seam = seam;
      const Measured r = synthesise(sample, o);
      EXPECT_EQ(r.result.image.width, o.width);
      EXPECT_EQ(r.result.image.height, o.height);
      EXPECT_EQ(r.result.image.channels, sample.channels);
      expectEveryPixelFromTheSample(sample, r.result);
      // The search picks blocks that fit: far less overlap error than random placement.
      EXPECT_LT(r.result.stats.overlap_error_per_pixel, 0.5 * baseline.result.stats.overlap_error_per_pixel);
      if (seam != SeamMode::None) {
        EXPECT_LT(r.metrics.seam_error_per_edge, baseline.metrics.seam_error_per_edge);
      }
    }
  }
}

TEST(Quilt, SeamsCutAlongLowErrorPaths) {
  const fs::path f = test::sharedData() / "textures/efros_t3.png";
  SHANSHUI_REQUIRE_FILE(f);
  const image::Image sample = image::loadImage(f);
  QuiltOptions o;
  o.width = o.height = 256;
  o.block = 40;
  o.seam = SeamMode::None;
  const double none = synthesise(sample, o).metrics.seam_error_per_edge;
  o.seam = SeamMode::Cut;
  const double cut = synthesise(sample, o).metrics.seam_error_per_edge;
  o.seam = SeamMode::GraphCut;
  const double graph = synthesise(sample, o).metrics.seam_error_per_edge;
  EXPECT_LT(cut, none);
  EXPECT_LT(graph, none);
}

TEST(Quilt, SameSeedSameOutputForAnyThreadCount) {
  const fs::path f = test::sharedData() / "textures/efros_t1.png";
  SHANSHUI_REQUIRE_FILE(f);
  const image::Image sample = image::loadImage(f);
  for (bool tileable : {false, true}) {
    for (SeamMode seam : {SeamMode::Cut, SeamMode::GraphCut}) {
      QuiltOptions o;
      o.width = 200;
      o.height = 170;
      o.block = 36;
      o.tileable = tileable;
      o.seam = seam;
      o.threads = 1;
      const QuiltResult one = quilt(sample, o);
      for (int threads : {2, 3, 8}) {
        o.threads = threads;
        const QuiltResult many = quilt(sample, o);
        EXPECT_EQ(one.image.pixels, many.image.pixels) << threads << " threads, tileable " << tileable;
        EXPECT_EQ(one.source, many.source);
        EXPECT_EQ(one.stats.overlap_error_per_pixel, many.stats.overlap_error_per_pixel);
      }
      o.seed = 2;
      EXPECT_NE(one.source, quilt(sample, o).source) << "another seed gives another texture";
    }
  }
}

TEST(Quilt, FftAndExhaustiveSearchesGiveTheSameTexture) {
  // efros_t16 has two grey levels: its overlap errors tie exactly, which the candidate rule
  // must treat alike in both searches.
  for (const char* name : {"efros_t5.png", "efros_t16.png"}) {
    const fs::path f = test::sharedData() / "textures" / name;
    SHANSHUI_REQUIRE_FILE(f);
    const image::Image sample = image::loadImage(f);
    QuiltOptions o;
    o.width = 120;
    o.height = 100;
    o.block = 24;
    o.audit = true;
    const QuiltResult fft = quilt(sample, o);
    o.search = SearchMode::Exhaustive;
    const QuiltResult exact = quilt(sample, o);
    EXPECT_EQ(fft.source, exact.source) << name;
    // The chosen error stays within the tolerance of the exhaustive minimum (the ratio is
    // below 1 where that minimum is under the absolute floor).
    EXPECT_GT(fft.stats.search_error_ratio, 0.0);
    EXPECT_LE(fft.stats.search_error_ratio, 1.0 + o.tolerance + 1e-6);
    EXPECT_EQ(fft.stats.search_rule_violations, 0.0);
  }
}

TEST(Quilt, TileableOutputWrapsWithoutASeam) {
  const auto files = test::textureScans();
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    const image::Image sample = image::loadImage(f);
    QuiltOptions o;
    o.width = 170;  // not a multiple of the step: uneven block spacing must still wrap
    o.height = 130;
    o.block = std::min({32, sample.width, sample.height});
    o.tileable = true;
    const Measured tiled = synthesise(sample, o);
    expectEveryPixelFromTheSample(sample, tiled.result);
    o.tileable = false;
    const Measured plain = synthesise(sample, o);
    // Plain output: the wrap is one long seam between unrelated pixels. Tileable output: the
    // wrap pairs continue the sample almost everywhere, with a few cut seams.
    EXPECT_GT(plain.metrics.wrap_seam_edges, (o.width + o.height) * 9 / 10);
    EXPECT_LT(tiled.metrics.wrap_seam_edges, (o.width + o.height) / 10);
    EXPECT_LT(tiled.metrics.wrap_seam_error, 0.1 * plain.metrics.wrap_seam_error);
  }
}

QuiltOptions sized(int width, int height, int block, int overlap = -1) {
  QuiltOptions o;
  o.width = width;
  o.height = height;
  o.block = block;
  o.overlap = overlap;
  return o;
}

TEST(Quilt, SmallestLegalProblemsWork) {
  image::Image sample(3, 3, 1);
  for (int i = 0; i < 9; ++i) sample.pixels[i] = static_cast<float>(i) / 8.0f;
  for (bool tileable : {false, true}) {
    for (SeamMode seam : {SeamMode::Cut, SeamMode::GraphCut, SeamMode::None}) {
      QuiltOptions o;
      o.width = 3;
      o.height = 5;
      o.block = 3;
      o.overlap = 2;
      o.tileable = tileable;
      o.seam = seam;
      const QuiltResult r = quilt(sample, o);
      expectEveryPixelFromTheSample(sample, r);
    }
  }
  // A flat sample is legal: every candidate ties, the output is flat.
  const QuiltResult flat = quilt(image::Image(20, 20, 1, 0.5f), sized(64, 64, 10));
  for (float v : flat.image.pixels) ASSERT_EQ(v, 0.5f);
}

TEST(Quilt, BadOptionsNameTheParameterAndTheValue) {
  const image::Image sample(40, 30, 1, 0.5f);
  auto expectError = [&](QuiltOptions o, const std::string& words) {
    test::expectErrorNaming([&] { quilt(sample, o, "sample.png"); }, "", words);
  };
  expectError(sized(64, 64, 2), "block 2; expected at least 3");
  expectError(sized(64, 64, 31), "sample.png: sample is 40x30, smaller than block 31");
  expectError(sized(64, 64, 12, 12), "overlap 12; expected 1 <= overlap < block (12)");
  expectError(sized(64, 64, 12, 0), "overlap 0");
  expectError(sized(10, 100, 12), "output size 10x100 is smaller than block 12");
  QuiltOptions negative = sized(64, 64, 12);
  negative.tolerance = -1;
  expectError(negative, "tolerance -1");
  image::Image nan = sample;
  nan.pixels[7] = std::nanf("");
  test::expectErrorNaming([&] { quilt(nan, sized(64, 64, 12), "nan.exr"); }, "nan.exr", "NaN");
}

TEST(QuiltMetrics, AVerbatimCopyHasNoSeamsAndPerfectCoherence) {
  std::mt19937 rng(2);
  image::Image sample(48, 40, 1);
  for (float& v : sample.pixels) v = static_cast<float>(rng() % 256) / 255.0f;
  QuiltResult copy;
  copy.image = sample;
  copy.source.resize(48 * 40);
  for (int i = 0; i < 48 * 40; ++i) copy.source[i] = i;
  const QuiltMetrics m = measureQuilt(sample, copy, 16);
  EXPECT_EQ(m.seam_edges, 0);
  EXPECT_LT(m.coherence_max, 1e-9);
  EXPECT_DOUBLE_EQ(m.verbatim_copy_ratio, 1.0);
  EXPECT_DOUBLE_EQ(m.sample_coverage, 1.0);
  EXPECT_DOUBLE_EQ(m.usage_cv, 0.0);

  // Shuffled pixels: every neighbour pair is a seam, nothing is coherent.
  QuiltResult shuffled = copy;
  std::shuffle(shuffled.source.begin(), shuffled.source.end(), rng);
  for (int i = 0; i < 48 * 40; ++i) shuffled.image.pixels[i] = sample.pixels[shuffled.source[i]];
  const QuiltMetrics s = measureQuilt(sample, shuffled, 16);
  EXPECT_GT(s.seam_edges, 2 * 47 * 39);
  EXPECT_GT(s.coherence_mean, 0.01);
  EXPECT_LT(s.verbatim_copy_ratio, 0.01);
  EXPECT_DOUBLE_EQ(s.sample_coverage, 1.0);
}

}  // namespace
}  // namespace shanshui::texsynth
