// The look statistics' own thinning against OpenCV's (the library it replaces in the
// renderer, kept here as the oracle), and the stroke width it gives on drawn bars. No GL.
#include "shanshui/render/look_metrics.h"

#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

namespace shanshui::render {
namespace {

image::Image maskOf(const cv::Mat& bytes) {
  image::Image out(bytes.cols, bytes.rows, 1);
  for (int y = 0; y < bytes.rows; ++y) {
    for (int x = 0; x < bytes.cols; ++x) out.at(x, y, 0) = bytes.at<std::uint8_t>(y, x) ? 1.0f : 0.0f;
  }
  return out;
}

TEST(LookMetrics, ZhangSuenSkeletonIsOpenCvs) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coord(0, 199), size(1, 18);
  for (int trial = 0; trial < 12; ++trial) {
    // Discs, thick lines and speckle, touching the border too.
    cv::Mat bytes = cv::Mat::zeros(160, 200, CV_8U);
    for (int i = 0; i < 6; ++i) cv::circle(bytes, {coord(rng), coord(rng) % 160}, size(rng), 255, cv::FILLED);
    for (int i = 0; i < 6; ++i) {
      cv::line(bytes, {coord(rng), coord(rng) % 160}, {coord(rng), coord(rng) % 160}, 255, size(rng) / 2 + 1);
    }
    for (int i = 0; i < 300; ++i) bytes.at<std::uint8_t>(coord(rng) % 160, coord(rng)) = 255;
    cv::Mat expected;
    cv::ximgproc::thinning(bytes, expected, cv::ximgproc::THINNING_ZHANGSUEN);
    const image::Image ours = zhangSuenSkeleton(maskOf(bytes));
    int differ = 0, set = 0;
    for (int y = 0; y < bytes.rows; ++y) {
      for (int x = 0; x < bytes.cols; ++x) {
        differ += (ours.at(x, y, 0) > 0.5f) != (expected.at<std::uint8_t>(y, x) > 0);
        set += expected.at<std::uint8_t>(y, x) > 0;
      }
    }
    EXPECT_EQ(differ, 0) << "trial " << trial;
    EXPECT_GT(set, 50) << "trial " << trial;
  }
}

// A dark bar w pixels wide on white paper measures w wide (area over skeleton length; the
// skeleton is shorter than the bar by about its width, so long bars are used).
TEST(LookMetrics, DarkWidthOfABarIsItsWidth) {
  for (const int width : {2, 5, 9}) {
    image::Image rgb(400, 120, 3, 1.0f);
    for (int y = 60; y < 60 + width; ++y) {
      for (int x = 20; x < 380; ++x) {
        for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = 0.0f;
      }
    }
    const LookStatistics look = lookStatistics(rgb, glm::dvec3(1.0));
    EXPECT_NEAR(look.dark_width_px, width, 0.05 * width + 0.1) << width;
  }
}

// Marks of known count and areas on a one-megapixel sheet: single pixels (too small to
// count), Ls of three pixels and squares of 16, 64 and 256, apart from each other; their
// log2 areas give the interquartile range exactly.
TEST(LookMetrics, DarkMarksAreCountedAndTheirSizesSpreadAsDrawn) {
  image::Image ink(1000, 1000, 1, 0.0f);
  auto square = [&](int x0, int y0, int side) {
    for (int y = y0; y < y0 + side; ++y)
      for (int x = x0; x < x0 + side; ++x) ink.at(x, y, 0) = 0.9f;
  };
  std::vector<double> log_areas;
  int x = 10, y = 10;
  auto next = [&](int side) {
    x += side + 6;
    if (x > 950) {
      x = 10;
      y += 30;
    }
  };
  for (int i = 0; i < 40; ++i) {
    for (int side : {1, 4, 8, 16}) {
      square(x, y, side);
      if (side > 1) log_areas.push_back(std::log2(side * side));
      next(side);
    }
    // An L of three pixels: counted.
    ink.at(x, y, 0) = ink.at(x + 1, y, 0) = ink.at(x, y + 1, 0) = 0.9f;
    log_areas.push_back(std::log2(3.0));
    next(2);
  }
  // Faint ink (below a third) is no mark.
  for (int i = 0; i < 200; ++i)
    ink.at(5 + 4 * i, 990, 0) = ink.at(6 + 4 * i, 990, 0) = ink.at(5 + 4 * i, 991, 0) = 0.3f;
  const auto [per_mp, spread] = darkMarks(ink);
  EXPECT_NEAR(per_mp, 160.0, 1e-9);
  // Areas 3, 16, 64, 256, forty of each; the quartiles interpolated between order statistics
  // 39 and 40, 119 and 120 of the 160.
  std::sort(log_areas.begin(), log_areas.end());
  const double q1 = log_areas[39] + 0.75 * (log_areas[40] - log_areas[39]);
  const double q3 = log_areas[119] + 0.25 * (log_areas[120] - log_areas[119]);
  EXPECT_NEAR(spread, q3 - q1, 1e-9);
  // The same sheet at twice the size is resampled to one megapixel: the same count.
  image::Image big(2000, 2000, 1, 0.0f);
  for (int yy = 0; yy < 2000; ++yy)
    for (int xx = 0; xx < 2000; ++xx) big.at(xx, yy, 0) = ink.at(xx / 2, yy / 2, 0);
  EXPECT_NEAR(darkMarks(big).first, 160.0, 1e-9);
}

}  // namespace
}  // namespace shanshui::render
