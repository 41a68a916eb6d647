#include "shanshui/render/look_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <tuple>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "shanshui/core/error.h"

namespace shanshui::render {

namespace {

double luminance(double r, double g, double b) {
  return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

// Zhang–Suen thinning of a 0/255 mask, as cv::ximgproc::thinning(THINNING_ZHANGSUEN) does
// it (LookMetrics.ZhangSuenSkeletonIsOpenCvs holds the two equal). Written here because linking opencv_ximgproc pulls
// dnn, calib3d and ~140 other libraries into every shanshui-render start (+85 ms).
// A pixel's eight neighbours, clockwise from north (p2 ... p9), form an 8-bit code; a
// table per sub-iteration says whether a set pixel with that neighbourhood is removed.
cv::Mat zhangSuenThinning(const cv::Mat& mask) {
  std::array<std::array<bool, 256>, 2> removable{};
  for (int code = 0; code < 256; ++code) {
    std::array<int, 8> p{};  // p[0] = p2 (north) ... p[7] = p9 (north-west)
    int set = 0, rises = 0;
    for (int k = 0; k < 8; ++k) {
      p[k] = (code >> k) & 1;
      set += p[k];
    }
    for (int k = 0; k < 8; ++k) rises += p[k] == 0 && p[(k + 1) % 8] == 1;
    const bool shape = rises == 1 && set >= 2 && set <= 6;
    // p2 p4 p6 = p[0] p[2] p[4]; p4 p6 p8 = p[2] p[4] p[6]; p2 p4 p8; p2 p6 p8.
    removable[0][code] = shape && !(p[0] && p[2] && p[4]) && !(p[2] && p[4] && p[6]);
    removable[1][code] = shape && !(p[0] && p[2] && p[6]) && !(p[0] && p[4] && p[6]);
  }
  cv::Mat img = mask / 255;
  cv::Mat marker(img.size(), CV_8U);
  for (bool changed = true; changed;) {
    changed = false;
    for (int pass = 0; pass < 2; ++pass) {
      marker.setTo(0);
      for (int y = 1; y + 1 < img.rows; ++y) {
        const std::uint8_t* up = img.ptr<std::uint8_t>(y - 1);
        const std::uint8_t* row = img.ptr<std::uint8_t>(y);
        const std::uint8_t* down = img.ptr<std::uint8_t>(y + 1);
        std::uint8_t* out = marker.ptr<std::uint8_t>(y);
        for (int x = 1; x + 1 < img.cols; ++x) {
          if (!row[x]) continue;
          const int code = up[x] | up[x + 1] << 1 | row[x + 1] << 2 | down[x + 1] << 3 | down[x] << 4 |
                           down[x - 1] << 5 | row[x - 1] << 6 | up[x - 1] << 7;
          out[x] = removable[pass][code];
        }
      }
      if (cv::countNonZero(marker) > 0) {
        changed = true;
        img.setTo(0, marker);
      }
    }
  }
  return img * 255;
}

}  // namespace

image::Image zhangSuenSkeleton(const image::Image& mask) {
  SHANSHUI_CHECK(mask.channels == 1);
  cv::Mat bytes(mask.height, mask.width, CV_8U);
  for (int y = 0; y < mask.height; ++y) {
    for (int x = 0; x < mask.width; ++x) bytes.at<std::uint8_t>(y, x) = mask.at(x, y, 0) > 0.5f ? 255 : 0;
  }
  const cv::Mat skeleton = zhangSuenThinning(bytes);
  image::Image out(mask.width, mask.height, 1);
  for (int y = 0; y < mask.height; ++y) {
    for (int x = 0; x < mask.width; ++x) out.at(x, y, 0) = skeleton.at<std::uint8_t>(y, x) ? 1.0f : 0.0f;
  }
  return out;
}

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
    const cv::Mat skeleton = zhangSuenThinning(dark);
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
  image::Image ink_image(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) ink_image.at(x, y, 0) = ink.at<float>(y, x);
  std::tie(out.marks_per_mp, out.mark_size_spread) = darkMarks(ink_image);
  return out;
}

std::pair<double, double> darkMarks(const image::Image& ink) {
  SHANSHUI_CHECK(ink.channels == 1 && ink.width > 0 && ink.height > 0);
  cv::Mat full(ink.height, ink.width, CV_32F);
  for (int y = 0; y < ink.height; ++y)
    for (int x = 0; x < ink.width; ++x) full.at<float>(y, x) = ink.at(x, y, 0);
  // At one megapixel, whatever the picture's size: a mark is measured at the scale the
  // paintings it is compared with were.
  const double scale = std::sqrt(1e6 / (static_cast<double>(ink.width) * ink.height));
  const cv::Size size(std::max(1, static_cast<int>(std::lround(ink.width * scale))),
                      std::max(1, static_cast<int>(std::lround(ink.height * scale))));
  cv::Mat mp;
  cv::resize(full, mp, size, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  const cv::Mat dark = mp > 1.0f / 3.0f;
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(dark, labels, stats, centroids, 8, CV_32S);
  std::vector<double> sizes;
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area >= 3) sizes.push_back(std::log2(static_cast<double>(area)));
  }
  const double per_mp = static_cast<double>(sizes.size()) / (static_cast<double>(size.area()) / 1e6);
  if (sizes.size() < 4) return {per_mp, 0.0};
  std::sort(sizes.begin(), sizes.end());
  auto at = [&](double q) {  // linear interpolation between order statistics
    const double k = q * static_cast<double>(sizes.size() - 1);
    const auto i = static_cast<std::size_t>(k);
    return sizes[i] + (k - static_cast<double>(i)) * (sizes[std::min(i + 1, sizes.size() - 1)] - sizes[i]);
  };
  return {per_mp, at(0.75) - at(0.25)};
}

}  // namespace shanshui::render
