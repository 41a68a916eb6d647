// Heights stored in steps, smoothed within their steps (heightfield.h's dequantize).

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "shanshui/terrain/heightfield.h"

namespace shanshui::terrain {

namespace {

// A sample lies on the step's lattice when it is within this share of a step of it: text
// DEMs give tenths as the nearest double ("42.1"), and the sums and scalings the readers do
// (feet to metres, a band's scale) add rounding of about 1e-16 of the height.
constexpr double kOnLattice = 1e-3;

}  // namespace

double heightStep(const Heightfield& h) {
  const auto [lo, hi] = h.elevationRange();
  if (std::isnan(lo) || !(hi > lo)) return 0.0;
  // The least height difference between neighbouring samples that is not zero: on a
  // staircase, one step (a surface smooth at the scale of the grid has neighbours one
  // step apart wherever it is gentle).
  double least = std::numeric_limits<double>::infinity();
  auto neighbours = [&](std::size_t a, std::size_t b) {
    const double d = std::abs(h.elevation[a] - h.elevation[b]);
    if (d > 0.0 && d < least) least = d;  // NaN compares false
  };
  const std::size_t w = static_cast<std::size_t>(h.columns), n = static_cast<std::size_t>(h.rows);
  for (std::size_t r = 0; r < n; ++r) {
    for (std::size_t c = 0; c < w; ++c) {
      if (c + 1 < w) neighbours(r * w + c, r * w + c + 1);
      if (r + 1 < n) neighbours(r * w + c, (r + 1) * w + c);
    }
  }
  // Too coarse a step to be a storage step (a terrace model, a mesa of three levels), or one
  // at the rounding of doubles: not stored in steps.
  if (!std::isfinite(least) || least > (hi - lo) / 8.0 || least < 1e-9 * std::max(std::abs(lo), std::abs(hi)))
    return 0.0;
  for (double z : h.elevation) {
    if (std::isnan(z)) continue;
    const double k = (z - lo) / least;
    if (std::abs(k - std::round(k)) > kOnLattice) return 0.0;
  }
  return least;
}

namespace {

// Smooths rows [top, bottom) x columns [left, right) of `h` (sweeps of the kernel, each
// held within half a step) and writes rows [keep_top, keep_bottom) of the result to `out`,
// a grid of the columns [left, right) from row `out_top`. The window's edges are extended as
// the grid's are: right at the grid's edge and at a row or column of no data, wrong within
// `sweeps` reaches of the kernel of any other edge, so rows that near one are not kept.
void smoothWindow(const Heightfield& h, double sigma, int sweeps, double half, int top, int bottom, int left, int right,
                  int keep_top, int keep_bottom, int out_top, std::vector<double>& out) {
  const int w = right - left, n = bottom - top, columns = h.columns;
  auto at = [&](int r, int c) { return h.elevation[static_cast<std::size_t>(top + r) * columns + left + c]; };
  // The stored heights and which samples hold one; no-data samples take no part (each blur
  // is normalised by the weight of the valid samples it covers) and stay no data.
  cv::Mat stored(n, w, CV_64F), valid(n, w, CV_64F);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < w; ++c) {
      const double z = at(r, c);
      stored.at<double>(r, c) = std::isnan(z) ? 0.0 : z;
      valid.at<double>(r, c) = std::isnan(z) ? 0.0 : 1.0;
    }
  }
  // The smoothing kernel: twice a Gaussian of sigma less one of sigma·√2. Its second moments
  // cancel, so it leaves every quadratic (and cubic) surface as it is: a hill's curved top is
  // not flattened, as a Gaussian alone would flatten it by sigma²/2 times its Laplacian (more
  // than half a step on the sample hill), and its powers, the sweeps, keep that.
  const double wide = sigma * std::numbers::sqrt2;
  // Beyond the grid's edges the heights go on as the edge's tangent would (2·edge − the
  // sample as far inside), so a ramp stays a ramp to its last sample instead of being bent
  // towards the inside (a replicated edge pulled a ramp's end samples in by half a step).
  // A padded sample counts where both samples it comes from hold a height (the weights
  // extended by a product, made once; the heights by the tangent, each sweep).
  const int pad = dequantizeReach(sigma);
  auto extend = [&](const cv::Mat& inside, auto beyond) {
    cv::Mat m(n + 2 * pad, w + 2 * pad, CV_64F, cv::Scalar(0.0));
    inside.copyTo(m(cv::Rect(pad, pad, w, n)));
    for (int r = pad; r < pad + n; ++r) {
      for (int j = 1; j <= pad; ++j) {
        const int k = std::min(j, w - 1), e = pad + w - 1;
        m.at<double>(r, pad - j) = beyond(m.at<double>(r, pad), m.at<double>(r, pad + k));
        m.at<double>(r, e + j) = beyond(m.at<double>(r, e), m.at<double>(r, e - k));
      }
    }
    for (int j = 1; j <= pad; ++j) {
      const int k = std::min(j, n - 1), e = pad + n - 1;
      for (int c = 0; c < w + 2 * pad; ++c) {
        m.at<double>(pad - j, c) = beyond(m.at<double>(pad, c), m.at<double>(pad + k, c));
        m.at<double>(e + j, c) = beyond(m.at<double>(e, c), m.at<double>(e - k, c));
      }
    }
    return m;
  };
  const cv::Mat weight = extend(valid, [](double edge, double in) { return edge * in; });
  auto blur = [&](const cv::Mat& m, double s) {
    cv::Mat b;
    cv::GaussianBlur(m, b, cv::Size(), s, s, cv::BORDER_REPLICATE);
    return b(cv::Rect(pad, pad, w, n)).clone();
  };
  cv::Mat z = stored.clone();
  const cv::Mat weight_near = blur(weight, sigma), weight_wide = blur(weight, wide);
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    const cv::Mat masked = extend(z, [](double edge, double in) { return 2.0 * edge - in; }).mul(weight);
    const cv::Mat near = blur(masked, sigma), far = blur(masked, wide);
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < w; ++c) {
        if (valid.at<double>(r, c) == 0.0) continue;
        const double smooth = 2.0 * near.at<double>(r, c) / weight_near.at<double>(r, c) -
                              far.at<double>(r, c) / weight_wide.at<double>(r, c);
        // Held within half a step of the stored height: what the file says, to its precision.
        const double s = stored.at<double>(r, c);
        z.at<double>(r, c) = std::clamp(smooth, s - half, s + half);
      }
    }
  }
  for (int r = keep_top - top; r < keep_bottom - top; ++r) {
    for (int c = 0; c < w; ++c) {
      if (valid.at<double>(r, c) != 0.0) out[static_cast<std::size_t>(top + r - out_top) * w + c] = z.at<double>(r, c);
    }
  }
}

}  // namespace

int dequantizeReach(double sigma) {
  // OpenCV's kernel for doubles reaches 4 sigma; the wider of the two Gaussians is sigma·√2.
  return static_cast<int>(std::ceil(4.0 * sigma * std::numbers::sqrt2)) + 1;
}

Dequantized dequantize(Heightfield& h, double sigma, int sweeps, std::size_t band_samples) {
  Dequantized out;
  out.step = heightStep(h);
  if (out.step <= 0.0 || sweeps <= 0 || !(sigma > 0.0)) return out;
  const int w = h.columns, n = h.rows;
  // Only the box around the samples that hold a height, and one row or column of no data
  // around it where the grid has one (beyond a row of no data nothing is used): a grid of
  // 25112 x 4116 samples of which 492 hold a height took 32 s and 9 GB.
  int left = w, right = -1, top = n, bottom = -1;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < w; ++c) {
      if (std::isnan(h.elevation[static_cast<std::size_t>(r) * w + c])) continue;
      left = std::min(left, c), right = std::max(right, c), top = std::min(top, r), bottom = std::max(bottom, r);
    }
  }
  if (right < 0) return out;  // heightStep found no step on a grid without heights
  left = std::max(left - 1, 0), top = std::max(top - 1, 0), right = std::min(right + 2, w),
  bottom = std::min(bottom + 2, n);
  // In bands of rows, each smoothed with an apron of rows beyond it that the sweeps' reach
  // cannot see past, so memory is a band's (about a dozen doubles a sample) whatever the
  // grid's size, and the result is the whole grid's.
  const int apron = (sweeps + 1) * dequantizeReach(sigma);
  const std::size_t box = static_cast<std::size_t>(right - left);
  const int rows_per_band = static_cast<int>(std::clamp<std::size_t>(band_samples / box, 1, n));
  std::vector<double> smoothed(box * static_cast<std::size_t>(bottom - top));
  for (int band = top; band < bottom; band += rows_per_band) {
    const int band_end = std::min(band + rows_per_band, bottom);
    smoothWindow(h, sigma, sweeps, 0.5 * out.step, std::max(band - apron, top), std::min(band_end + apron, bottom),
                 left, right, band, band_end, top, smoothed);
  }
  for (int r = top; r < bottom; ++r) {
    for (int c = left; c < right; ++c) {
      double& e = h.elevation[static_cast<std::size_t>(r) * w + c];
      if (std::isnan(e)) continue;
      const double z = smoothed[static_cast<std::size_t>(r - top) * box + (c - left)];
      out.largest_change = std::max(out.largest_change, std::abs(z - e));
      e = z;
    }
  }
  std::ostringstream note;
  note << "heights stored in steps of " << out.step << " m smoothed within half a step (at most " << out.largest_change
       << " m moved), so flat ground is not drawn as terraces";
  h.notes.push_back(note.str());
  return out;
}

}  // namespace shanshui::terrain
