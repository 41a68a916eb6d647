// The overlap error of image quilting (Efros & Freeman 2001; SPEC.md section 3, step 2):
// for every block-sized window of the sample, the sum of squared differences to the pixels
// already synthesised in the block's footprint.
#pragma once

#include <opencv2/core.hpp>

#include "shanshui/image/image.h"

namespace shanshui::texsynth {

enum class SearchMode {
  Fft,         //!< all windows at once by FFT correlation (exact up to rounding)
  Exhaustive,  //!< direct sum per window: the reference
  Random,      //!< no search: uniform placement (the baseline quilting must beat)
};

const char* searchModeName(SearchMode mode);

//! Holds the sample and its spectra so that each query costs a few FFTs of sample size.
//! Thread-safe for concurrent errors() calls.
class OverlapSearch {
 public:
  //! `block` is the window size B; the sample must be at least B×B.
  OverlapSearch(const image::Image& sample, int block);

  int block() const { return block_; }
  //! Window positions: x in [0, positionsX()), y in [0, positionsY()).
  int positionsX() const { return sample_.width - block_ + 1; }
  int positionsY() const { return sample_.height - block_ + 1; }

  //! E(y, x) = sum over q with mask(q) != 0 and channels c of (patch(q, c) − sample(x + q, c))²
  //! as a CV_64F matrix of positionsY() × positionsX(). `patch` is B×B with the sample's
  //! channels; `mask` is B×B CV_8U. Mode Random is not a search and is refused.
  cv::Mat errors(const image::Image& patch, const cv::Mat& mask, SearchMode mode) const;

  //! The same into `out`, reusing its memory when it already has the right size: the FFT
  //! buffers are per thread and reused too, so repeated queries allocate nothing (large
  //! allocations are mmap calls, which serialise threads in the kernel).
  void errors(const image::Image& patch, const cv::Mat& mask, SearchMode mode, cv::Mat& out) const;

  //! The same sum for one window, computed directly.
  double errorAt(const image::Image& patch, const cv::Mat& mask, int x, int y) const;

 private:
  void fftErrors(const image::Image& patch, const cv::Mat& mask, cv::Mat& out) const;
  void exhaustiveErrors(const image::Image& patch, const cv::Mat& mask, cv::Mat& out) const;

  image::Image sample_;
  int block_;
  cv::Size dftSize_;
  std::vector<cv::Mat> channelSpectra_;  //!< DFT of each sample channel (CCS packed)
  cv::Mat squareSpectrum_;               //!< DFT of the per-pixel sum of squares
};

}  // namespace shanshui::texsynth
