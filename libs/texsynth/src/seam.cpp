#include "shanshui/texsynth/seam.h"

#include "shanshui/core/error.h"
#include "shanshui/texsynth/min_error_cut.h"

namespace shanshui::texsynth {

const char* seamModeName(SeamMode mode) {
  switch (mode) {
    case SeamMode::Cut:
      return "cut";
    case SeamMode::GraphCut:
      return "graphcut";
    case SeamMode::None:
      return "none";
  }
  return "?";
}

OverlapStrips overlapStrips(const cv::Mat& filled) {
  SHANSHUI_CHECK_EQ(filled.type(), CV_8U);
  SHANSHUI_CHECK_EQ(filled.rows, filled.cols);
  const int b = filled.rows;
  auto columnFull = [&](int x) {
    for (int y = 0; y < b; ++y) {
      if (!filled.at<std::uint8_t>(y, x)) return false;
    }
    return true;
  };
  auto rowFull = [&](int y) {
    for (int x = 0; x < b; ++x) {
      if (!filled.at<std::uint8_t>(y, x)) return false;
    }
    return true;
  };
  OverlapStrips s;
  while (s.left < b && columnFull(s.left)) ++s.left;
  while (s.right < b && columnFull(b - 1 - s.right)) ++s.right;
  while (s.top < b && rowFull(s.top)) ++s.top;
  while (s.bottom < b && rowFull(b - 1 - s.bottom)) ++s.bottom;
  return s;
}

cv::Mat overlapDifference(const image::Image& old, const image::Image& patch, const cv::Mat& filled) {
  const int b = filled.rows;
  cv::Mat diff = cv::Mat::zeros(b, b, CV_64F);
  for (int y = 0; y < b; ++y) {
    for (int x = 0; x < b; ++x) {
      if (!filled.at<std::uint8_t>(y, x)) continue;
      double sum = 0.0;
      for (int c = 0; c < old.channels; ++c) {
        const double d = static_cast<double>(old.at(x, y, c)) - patch.at(x, y, c);
        sum += d * d;
      }
      diff.at<double>(y, x) = sum;
    }
  }
  return diff;
}

namespace {

// Minimum error cuts through each strip; a pixel is new when it is on the new side of
// every cut (for the corners that is the combination of the vertical and horizontal cuts).
cv::Mat dpCutMask(const cv::Mat& diff, const cv::Mat& filled) {
  const int b = filled.rows;
  const OverlapStrips s = overlapStrips(filled);
  cv::Mat isNew(b, b, CV_8U, cv::Scalar(1));
  if (s.left > 0) {
    const std::vector<int> path = minimumErrorPath(diff.colRange(0, s.left).clone());
    for (int y = 0; y < b; ++y) {
      for (int x = 0; x < path[y]; ++x) isNew.at<std::uint8_t>(y, x) = 0;
    }
  }
  if (s.right > 0) {
    const std::vector<int> path = minimumErrorPath(diff.colRange(b - s.right, b).clone());
    for (int y = 0; y < b; ++y) {
      for (int x = b - s.right + path[y] + 1; x < b; ++x) isNew.at<std::uint8_t>(y, x) = 0;
    }
  }
  if (s.top > 0) {
    const std::vector<int> path = minimumErrorPath(diff.rowRange(0, s.top).t());
    for (int x = 0; x < b; ++x) {
      for (int y = 0; y < path[x]; ++y) isNew.at<std::uint8_t>(y, x) = 0;
    }
  }
  if (s.bottom > 0) {
    const std::vector<int> path = minimumErrorPath(diff.rowRange(b - s.bottom, b).t());
    for (int x = 0; x < b; ++x) {
      for (int y = b - s.bottom + path[x] + 1; y < b; ++y) isNew.at<std::uint8_t>(y, x) = 0;
    }
  }
  return isNew;
}

}  // namespace

cv::Mat seamMask(const image::Image& old, const image::Image& patch, const cv::Mat& filled, SeamMode mode) {
  const int b = filled.rows;
  SHANSHUI_CHECK_EQ(old.width, b);
  SHANSHUI_CHECK_EQ(old.height, b);
  SHANSHUI_CHECK_EQ(patch.width, b);
  SHANSHUI_CHECK_EQ(patch.height, b);
  SHANSHUI_CHECK_EQ(old.channels, patch.channels);
  cv::Mat isNew;
  switch (mode) {
    case SeamMode::None:
      isNew = cv::Mat(b, b, CV_8U, cv::Scalar(1));
      break;
    case SeamMode::Cut:
      isNew = dpCutMask(overlapDifference(old, patch, filled), filled);
      break;
    case SeamMode::GraphCut:
      isNew = graphCutMask(old, patch, filled);
      break;
  }
  isNew.setTo(1, filled == 0);  // nothing to keep where nothing is yet
  return isNew;
}

}  // namespace shanshui::texsynth
