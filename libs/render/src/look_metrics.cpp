#include "shanshui/render/look_metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc.hpp>

#include "shanshui/core/error.h"

namespace shanshui::render {

namespace {

double luminance(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

}  // namespace

LookStatistics lookStatistics(const image::Image& rgb, const glm::dvec3& paper, const image::Image* subject) {
  SHANSHUI_CHECK(rgb.channels >= 3 && rgb.width > 0 && rgb.height > 0);
  SHANSHUI_CHECK(!subject || (subject->width == rgb.width && subject->height == rgb.height));
  const int w = rgb.width, h = rgb.height;
  const double paper_lum = std::max(luminance(paper.x, paper.y, paper.z), 1e-6);
  cv::Mat ink(h, w, CV_32F);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double lum = luminance(rgb.at(x, y, 0), rgb.at(x, y, 1), rgb.at(x, y, 2));
      ink.at<float>(y, x) = static_cast<float>(std::clamp(1.0 - lum / paper_lum, 0.0, 1.0));
    }
  }
  const double pixels = static_cast<double>(w) * h;
  LookStatistics out;
  out.paper_share = static_cast<double>(cv::countNonZero(ink < 0.1f)) / pixels;

  const cv::Mat dark = ink > 0.5f;  // 255 where dark
  const int dark_area = cv::countNonZero(dark);
  out.dark_share = dark_area / pixels;
  if (dark_area > 0) {
    cv::Mat skeleton;
    cv::ximgproc::thinning(dark, skeleton, cv::ximgproc::THINNING_ZHANGSUEN);
    out.dark_width_px = static_cast<double>(dark_area) / std::max(cv::countNonZero(skeleton), 1);
  }

  // The subject's rows, split in thirds.
  auto inSubject = [&](int x, int y) { return subject ? subject->at(x, y, 0) > 0.5f : ink.at<float>(y, x) > 0.1f; };
  int first = h, last = -1;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (inSubject(x, y)) {
        first = std::min(first, y);
        last = std::max(last, y);
        break;
      }
    }
  }
  if (last >= first) {
    const double rows = last - first + 1;
    double sum[3] = {0, 0, 0}, count[3] = {0, 0, 0};
    for (int y = first; y <= last; ++y) {
      const int third = std::min(2, static_cast<int>(3.0 * (y - first) / rows));
      for (int x = 0; x < w; ++x) {
        if (!inSubject(x, y)) continue;
        sum[third] += ink.at<float>(y, x);
        count[third] += 1;
      }
    }
    const double far = count[0] > 0 ? sum[0] / count[0] : 0.0, near = count[2] > 0 ? sum[2] / count[2] : 0.0;
    out.far_near_ink = near > 0 ? far / near : 0.0;
  }

  cv::Mat ink8, edges;
  ink.convertTo(ink8, CV_8U, 255.0);
  cv::Canny(ink8, edges, 40, 120);
  std::vector<cv::Vec4i> segments;
  cv::HoughLinesP(edges, segments, 1, std::numbers::pi / 180, 30, std::max(8.0, 0.05 * w), 2);
  for (const cv::Vec4i& s : segments) {
    out.longest_straight = std::max(out.longest_straight, std::hypot(s[2] - s[0], s[3] - s[1]) / w);
  }
  return out;
}

}  // namespace shanshui::render
