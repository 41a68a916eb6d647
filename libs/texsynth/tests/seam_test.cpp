// Seams: the dynamic-programming cut against brute force, and the graph cut against the
// DP cut where both must give the same picture.
#include "shanshui/texsynth/seam.h"

#include <random>

#include "shanshui/texsynth/min_error_cut.h"
#include "test_support.h"

namespace shanshui::texsynth {
namespace {

// Least cost over every path that moves at most one column per row (enumerated).
double bruteForceMinimum(const cv::Mat& cost) {
  const int rows = cost.rows, cols = cost.cols;
  double best = std::numeric_limits<double>::infinity();
  std::vector<int> path(rows, 0);
  std::function<void(int, double)> extend = [&](int r, double sum) {
    if (r == rows) {
      best = std::min(best, sum);
      return;
    }
    for (int c = 0; c < cols; ++c) {
      if (r > 0 && std::abs(c - path[r - 1]) > 1) continue;
      path[r] = c;
      extend(r + 1, sum + cost.at<double>(r, c));
    }
  };
  extend(0, 0.0);
  return best;
}

TEST(MinimumErrorCut, MatchesBruteForceOnTinyStrips) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int cols = 1; cols <= 4; ++cols) {
    for (int rows = 1; rows <= 6; ++rows) {
      for (int trial = 0; trial < 20; ++trial) {
        cv::Mat cost(rows, cols, CV_64F);
        for (int i = 0; i < rows * cols; ++i)
          cost.at<double>(i / cols, i % cols) = trial % 5 == 0 ? std::floor(u(rng) * 3) : u(rng);
        const std::vector<int> path = minimumErrorPath(cost);
        ASSERT_EQ(static_cast<int>(path.size()), rows);
        for (int r = 0; r < rows; ++r) {
          ASSERT_GE(path[r], 0);
          ASSERT_LT(path[r], cols);
          if (r > 0) {
            ASSERT_LE(std::abs(path[r] - path[r - 1]), 1) << "path jumps at row " << r;
          }
        }
        EXPECT_NEAR(pathCost(cost, path), bruteForceMinimum(cost), 1e-12) << rows << "x" << cols << " trial " << trial;
      }
    }
  }
}

image::Image noise(int b, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  image::Image img(b, b, channels);
  for (float& v : img.pixels) v = u(rng);
  return img;
}

image::Image composite(const image::Image& old, const image::Image& patch, const cv::Mat& isNew) {
  image::Image out = old;
  for (int y = 0; y < old.height; ++y)
    for (int x = 0; x < old.width; ++x)
      for (int c = 0; c < old.channels; ++c)
        if (isNew.at<std::uint8_t>(y, x)) out.at(x, y, c) = patch.at(x, y, c);
  return out;
}

// Old and new agree on a two-pixel-wide band that wanders at most one column per row and
// differ strongly everywhere else in the overlap, so there is one zero-cost seam and both
// methods must produce the same picture: old left of the band, new right of it.
TEST(GraphCut, AgreesWithTheDynamicProgrammingCutOnAZeroCostBand) {
  const int b = 24, strip = 8;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937 rng(seed);
    const image::Image old = noise(b, 3, seed);
    image::Image patch = old;
    for (float& v : patch.pixels) v = 1.0f - v * 0.2f;  // far from old everywhere...
    std::vector<int> band(b);
    band[0] = 3;
    for (int y = 1; y < b; ++y) band[y] = std::clamp(band[y - 1] + static_cast<int>(rng() % 3) - 1, 1, strip - 3);
    for (int y = 0; y < b; ++y)
      for (int x = band[y]; x <= band[y] + 1; ++x)
        for (int c = 0; c < 3; ++c) patch.at(x, y, c) = old.at(x, y, c);  // ...except on the band
    cv::Mat filled = cv::Mat::zeros(b, b, CV_8U);
    filled.colRange(0, strip).setTo(1);

    const cv::Mat dp = seamMask(old, patch, filled, SeamMode::Cut);
    const cv::Mat gc = seamMask(old, patch, filled, SeamMode::GraphCut);
    const image::Image a = composite(old, patch, dp), g = composite(old, patch, gc);
    EXPECT_EQ(a.pixels, g.pixels) << "seed " << seed;
    for (int y = 0; y < b; ++y) {
      EXPECT_EQ(a.at(0, y), old.at(0, y)) << "left edge must stay old, row " << y;
      EXPECT_EQ(a.at(strip, y), patch.at(strip, y)) << "right of the overlap must be new, row " << y;
    }
  }
}

TEST(Seam, CornerCombinesTheVerticalAndHorizontalCuts) {
  const int b = 20, o = 5;
  const image::Image old = noise(b, 1, 3), patch = noise(b, 1, 4);
  cv::Mat filled = cv::Mat::zeros(b, b, CV_8U);
  filled.colRange(0, o).setTo(1);
  filled.rowRange(0, o).setTo(1);
  const OverlapStrips s = overlapStrips(filled);
  EXPECT_EQ(s.left, o);
  EXPECT_EQ(s.top, o);
  EXPECT_EQ(s.right, 0);
  EXPECT_EQ(s.bottom, 0);
  for (SeamMode mode : {SeamMode::Cut, SeamMode::GraphCut}) {
    const cv::Mat isNew = seamMask(old, patch, filled, mode);
    for (int y = 0; y < b; ++y) {
      for (int x = 0; x < b; ++x) {
        if (x >= o && y >= o) {
          EXPECT_TRUE(isNew.at<std::uint8_t>(y, x)) << "unfilled pixel kept old at " << x << "," << y;
        }
      }
    }
    EXPECT_FALSE(isNew.at<std::uint8_t>(0, 0)) << seamModeName(mode) << ": the shared corner stays old";
  }
  EXPECT_EQ(cv::countNonZero(seamMask(old, patch, filled, SeamMode::None)), b * b);
}

}  // namespace
}  // namespace shanshui::texsynth
