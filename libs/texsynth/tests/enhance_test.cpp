// Contrast enhancement (SPEC.md section 2) against OpenImageIO's contrast_remap + clamp,
// a sort-based percentile, and the piecewise definition of Eq. 4.
#include "shanshui/texsynth/enhance.h"

#include <algorithm>
#include <random>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "shanshui/image/convert.h"
#include "shanshui/image/image_io.h"
#include "test_support.h"

namespace shanshui::texsynth {
namespace {

namespace fs = std::filesystem;

// The oracle: OpenImageIO's linear contrast remap of every channel, then a clamp to [c, d].
image::Image oiioRemap(const image::Image& img, float a, float b, float c, float d) {
  const OIIO::ImageSpec spec(img.width, img.height, img.channels, OIIO::TypeDesc::FLOAT);
  const OIIO::ImageBuf src(spec, const_cast<float*>(img.pixels.data()));
  const OIIO::ImageBuf remapped = OIIO::ImageBufAlgo::contrast_remap(src, a, b, c, d);
  const OIIO::ImageBuf clamped = OIIO::ImageBufAlgo::clamp(remapped, std::min(c, d), std::max(c, d));
  image::Image out(img.width, img.height, img.channels);
  clamped.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, out.pixels.data());
  return out;
}

image::Image randomImage(int w, int h, int channels, int levels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> level(0, levels - 1);
  image::Image img(w, h, channels);
  for (float& v : img.pixels) v = static_cast<float>(level(rng)) / static_cast<float>(levels - 1);
  return img;
}

TEST(Enhance, MatchesOpenImageIOContrastRemapExactlyOnEveryTexture) {
  const auto files = test::textureScans();
  const ValueRange ranges[][2] = {{{0.2, 0.8}, {0.0, 1.0}}, {{0.1, 0.95}, {0.05, 0.9}}, {{0.3, 0.31}, {1.0, 0.0}}};
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    const image::Image img = image::loadImage(f);
    const image::Image grey = image::toGrey(img);
    for (const auto& r : ranges) {
      EnhanceOptions o;
      o.input_range = r[0];
      o.output_range = r[1];
      const image::Image ours = enhanceContrast(img, o);
      const image::Image oracle = oiioRemap(grey, static_cast<float>(r[0].low), static_cast<float>(r[0].high),
                                            static_cast<float>(r[1].low), static_cast<float>(r[1].high));
      ASSERT_EQ(ours.channels, 1);
      ASSERT_EQ(ours.pixels.size(), oracle.pixels.size());
      std::size_t mismatches = 0;
      for (std::size_t i = 0; i < ours.pixels.size(); ++i) mismatches += ours.pixels[i] != oracle.pixels[i];
      EXPECT_EQ(mismatches, 0u) << "range " << r[0].low << ":" << r[0].high << " -> " << r[1].low << ":" << r[1].high;
    }
  }
}

TEST(Enhance, ColourModeMapsEveryColourChannelAndKeepsAlpha) {
  const fs::path f = test::sharedData() / "textures/efros_t3.png";
  SHANSHUI_REQUIRE_FILE(f);
  const image::Image img = image::loadImage(f);
  ASSERT_EQ(img.channels, 4);
  EnhanceOptions o;
  o.input_range = ValueRange{0.25, 0.75};
  o.colour = true;
  const image::Image ours = enhanceContrast(img, o);
  const image::Image oracle = oiioRemap(img, 0.25f, 0.75f, 0.0f, 1.0f);
  ASSERT_EQ(ours.channels, 4);
  for (std::size_t p = 0; p < ours.pixels.size(); ++p) {
    if (p % 4 == 3) {
      ASSERT_EQ(ours.pixels[p], img.pixels[p]) << "alpha changed at " << p / 4;
    } else {
      ASSERT_EQ(ours.pixels[p], oracle.pixels[p]) << "pixel " << p / 4 << " channel " << p % 4;
    }
  }
}

TEST(Enhance, PercentilesMatchSortingFor8And16BitData) {
  for (int levels : {256, 65536}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const image::Image img = randomImage(173, 91, 1, levels, seed);
      std::vector<float> sorted = img.pixels;
      std::sort(sorted.begin(), sorted.end());
      for (double p : {0.0, 1.0, 2.5, 50.0, 99.0, 100.0}) {
        // Smallest value with at least p% of the values at or below it.
        const auto need = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(p / 100.0 * sorted.size())));
        const double expected = sorted[need - 1];
        const ValueRange r = percentileRange(img, p, p);
        EXPECT_NEAR(r.low, expected, 1e-7) << "levels " << levels << " p " << p;
      }
    }
  }
}

TEST(Enhance, FollowsThePiecewiseDefinition) {
  const image::Image img = randomImage(64, 64, 1, 65536, 9);
  EnhanceOptions o;
  o.input_range = ValueRange{0.3, 0.6};
  o.output_range = ValueRange{0.1, 0.9};
  const image::Image g = enhanceContrast(img, o);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const double f = img.pixels[i];
    const double expected = f <= 0.3 ? 0.1 : f > 0.6 ? 0.9 : 0.1 + 0.8 * (f - 0.3) / 0.3;
    ASSERT_NEAR(g.pixels[i], expected, 2e-6) << "f = " << f;
  }
}

TEST(Enhance, AutomaticRangeStretchesToTheFullRange) {
  const fs::path f = test::sharedData() / "textures/ink_landscape_scan.jpg";
  SHANSHUI_REQUIRE_FILE(f);
  const image::Image img = image::loadImage(f);
  EnhanceReport report;
  const image::Image g = enhanceContrast(img, EnhanceOptions{}, &report, f.string());
  // 1% / 99% percentiles: about 1% of the values end at each end.
  EXPECT_GT(report.input_range.high - report.input_range.low, 0.1);
  EXPECT_NEAR(report.clipped_low, 0.01, 0.01);
  EXPECT_NEAR(report.clipped_high, 0.01, 0.01);
  const auto [lo, hi] = std::minmax_element(g.pixels.begin(), g.pixels.end());
  EXPECT_EQ(*lo, 0.0f);
  EXPECT_EQ(*hi, 1.0f);
}

TEST(Enhance, BadInputNamesTheNumbers) {
  const image::Image img = randomImage(16, 16, 1, 256, 4);
  auto expectError = [](const image::Image& in, const EnhanceOptions& o, const std::string& words) {
    test::expectErrorNaming([&] { enhanceContrast(in, o, nullptr, "scan.png"); }, "", words);
  };
  EnhanceOptions o;
  o.input_range = ValueRange{0.6, 0.4};
  expectError(img, o, "0.6:0.4; b must be greater than a");
  o.input_range = ValueRange{0.5, 0.5};
  expectError(img, o, "b must be greater than a");
  o.input_range = ValueRange{-0.1, 0.5};
  expectError(img, o, "input range a = -0.1");
  o = {};
  o.output_range = {0.5, 0.5};
  expectError(img, o, "c and d must differ");
  o = {};
  o.low_percentile = 60;
  o.high_percentile = 40;
  expectError(img, o, "percentiles 60:40");
  expectError(image::Image(8, 8, 1, 0.42f), EnhanceOptions{}, "scan.png: no contrast");
  image::Image outside = img;
  outside.pixels[5] = 1.5f;
  expectError(outside, EnhanceOptions{}, "scan.png: 1 values outside [0, 1]");
  image::Image nan = img;
  nan.pixels[3] = std::nanf("");
  expectError(nan, EnhanceOptions{}, "scan.png: contains NaN");
  // Fully transparent: composited over white it is flat paper.
  expectError(image::Image(8, 8, 2, 0.0f), EnhanceOptions{}, "no contrast");
}

}  // namespace
}  // namespace shanshui::texsynth
