#include "shanshui/texsynth/overlap_search.h"

#include <algorithm>

#include "shanshui/core/error.h"

namespace shanshui::texsynth {

const char* searchModeName(SearchMode mode) {
  switch (mode) {
    case SearchMode::Fft:
      return "fft";
    case SearchMode::Exhaustive:
      return "exhaustive";
    case SearchMode::Random:
      return "random";
  }
  return "?";
}

OverlapSearch::OverlapSearch(const image::Image& sample, int block) : sample_(sample), block_(block) {
  SHANSHUI_CHECK_GE(block, 1);
  SHANSHUI_CHECK_LE(block, sample.width);
  SHANSHUI_CHECK_LE(block, sample.height);
  // Circular correlation of size >= the sample never wraps for windows that fit inside it,
  // so no padding beyond the next fast DFT size is needed.
  dftSize_ = {cv::getOptimalDFTSize(sample.width), cv::getOptimalDFTSize(sample.height)};
  cv::Mat squares = cv::Mat::zeros(dftSize_, CV_64F);
  for (int c = 0; c < sample.channels; ++c) {
    cv::Mat plane = cv::Mat::zeros(dftSize_, CV_64F);
    for (int y = 0; y < sample.height; ++y) {
      auto* row = plane.ptr<double>(y);
      auto* sq = squares.ptr<double>(y);
      for (int x = 0; x < sample.width; ++x) {
        const double v = sample.at(x, y, c);
        row[x] = v;
        sq[x] += v * v;
      }
    }
    cv::Mat spectrum;
    cv::dft(plane, spectrum, 0, sample.height);
    channelSpectra_.push_back(spectrum);
  }
  cv::dft(squares, squareSpectrum_, 0, sample.height);
}

cv::Mat OverlapSearch::errors(const image::Image& patch, const cv::Mat& mask, SearchMode mode) const {
  cv::Mat out;
  errors(patch, mask, mode, out);
  return out;
}

void OverlapSearch::errors(const image::Image& patch, const cv::Mat& mask, SearchMode mode, cv::Mat& out) const {
  SHANSHUI_CHECK_EQ(patch.width, block_);
  SHANSHUI_CHECK_EQ(patch.height, block_);
  SHANSHUI_CHECK_EQ(patch.channels, sample_.channels);
  SHANSHUI_CHECK_EQ(mask.type(), CV_8U);
  SHANSHUI_CHECK_EQ(mask.rows, block_);
  SHANSHUI_CHECK_EQ(mask.cols, block_);
  switch (mode) {
    case SearchMode::Fft:
      return fftErrors(patch, mask, out);
    case SearchMode::Exhaustive:
      return exhaustiveErrors(patch, mask, out);
    case SearchMode::Random:
      break;
  }
  throw makeError("overlap search: mode '", searchModeName(mode), "' computes no errors");
}

namespace {
// Per-thread FFT buffers; create() keeps the memory when the size does not change.
struct FftScratch {
  cv::Mat maskPlane, plane, spectrum, accum, product, correlation;
};
thread_local FftScratch scratch;
}  // namespace

void OverlapSearch::fftErrors(const image::Image& patch, const cv::Mat& mask, cv::Mat& out) const {
  // E(p) = sum M T² − 2 sum_c corr(I_c, M T_c)(p) + corr(sum_c I_c², M)(p); the two
  // correlations are summed in the frequency domain and transformed back once.
  const int b = block_;
  double templateEnergy = 0.0;
  cv::Mat& maskPlane = scratch.maskPlane;
  maskPlane.create(dftSize_, CV_64F);
  maskPlane.setTo(0.0);
  for (int y = 0; y < b; ++y) {
    for (int x = 0; x < b; ++x) {
      if (!mask.at<std::uint8_t>(y, x)) continue;
      maskPlane.at<double>(y, x) = 1.0;
      for (int c = 0; c < patch.channels; ++c) {
        const double t = patch.at(x, y, c);
        templateEnergy += t * t;
      }
    }
  }
  cv::Mat& spectrum = scratch.spectrum;
  cv::Mat& accum = scratch.accum;
  cv::Mat& product = scratch.product;
  cv::dft(maskPlane, spectrum, 0, b);
  cv::mulSpectrums(squareSpectrum_, spectrum, accum, 0, /*conjB=*/true);
  cv::Mat& plane = scratch.plane;
  plane.create(dftSize_, CV_64F);
  plane.setTo(0.0);
  for (int c = 0; c < patch.channels; ++c) {
    for (int y = 0; y < b; ++y) {
      for (int x = 0; x < b; ++x) {
        plane.at<double>(y, x) = mask.at<std::uint8_t>(y, x) ? patch.at(x, y, c) : 0.0;
      }
    }
    cv::dft(plane, spectrum, 0, b);
    cv::mulSpectrums(channelSpectra_[c], spectrum, product, 0, /*conjB=*/true);
    cv::scaleAdd(product, -2.0, accum, accum);
  }
  cv::Mat& correlation = scratch.correlation;
  cv::dft(accum, correlation, cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE, positionsY());
  out.create(positionsY(), positionsX(), CV_64F);
  for (int y = 0; y < positionsY(); ++y) {
    const double* in = correlation.ptr<double>(y);
    double* row = out.ptr<double>(y);
    // Rounding can leave tiny negative values where the true error is 0.
    for (int x = 0; x < positionsX(); ++x) row[x] = std::max(in[x] + templateEnergy, 0.0);
  }
}

void OverlapSearch::exhaustiveErrors(const image::Image& patch, const cv::Mat& mask, cv::Mat& out) const {
  struct Tap {
    int offset;  // index of the first channel in the sample, relative to the window origin
    int patchIndex;
  };
  std::vector<Tap> taps;
  for (int y = 0; y < block_; ++y) {
    for (int x = 0; x < block_; ++x) {
      if (mask.at<std::uint8_t>(y, x)) {
        taps.push_back({static_cast<int>(sample_.index(x, y)), static_cast<int>(patch.index(x, y))});
      }
    }
  }
  const int channels = sample_.channels;
  out.create(positionsY(), positionsX(), CV_64F);
  for (int py = 0; py < positionsY(); ++py) {
    for (int px = 0; px < positionsX(); ++px) {
      const float* origin = &sample_.pixels[sample_.index(px, py)];
      double sum = 0.0;
      for (const Tap& t : taps) {
        for (int c = 0; c < channels; ++c) {
          const double d = static_cast<double>(patch.pixels[t.patchIndex + c]) - origin[t.offset + c];
          sum += d * d;
        }
      }
      out.at<double>(py, px) = sum;
    }
  }
}

double OverlapSearch::errorAt(const image::Image& patch, const cv::Mat& mask, int x, int y) const {
  double sum = 0.0;
  for (int v = 0; v < block_; ++v) {
    for (int u = 0; u < block_; ++u) {
      if (!mask.at<std::uint8_t>(v, u)) continue;
      for (int c = 0; c < sample_.channels; ++c) {
        const double d = static_cast<double>(patch.at(u, v, c)) - sample_.at(x + u, y + v, c);
        sum += d * d;
      }
    }
  }
  return sum;
}

}  // namespace shanshui::texsynth
