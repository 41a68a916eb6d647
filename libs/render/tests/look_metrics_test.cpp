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

}  // namespace
}  // namespace shanshui::render
