// Contrast enhancement of scanned wrinkle (cun) samples: the piecewise linear grey-level
// transform of seed 001, Eq. 4 (SPEC.md section 2).
#pragma once

#include <optional>
#include <string>

#include "shanshui/image/image.h"

namespace shanshui::texsynth {

struct ValueRange {
  double low = 0.0;
  double high = 1.0;
};

//! g = c for f <= a, c + (d - c)(f - a)/(b - a) for a < f <= b, d for f > b.
struct EnhanceOptions {
  //! [a, b], explicit; 0 <= a < b <= 1. When absent it comes from the percentiles below.
  std::optional<ValueRange> input_range;
  double low_percentile = 1.0;    //!< percent of values at or below a, [0, 100)
  double high_percentile = 99.0;  //!< percent of values at or below b, (low, 100]
  ValueRange output_range;        //!< [c, d], each in [0, 1], c != d (c > d inverts)
  //! false: one grey channel (alpha composited over white, luma weights); true: the same
  //! map on every colour channel, alpha kept as it is.
  bool colour = false;
};

struct EnhanceReport {
  ValueRange input_range;     //!< the [a, b] used (given or from the percentiles)
  double clipped_low = 0.0;   //!< fraction of values at or below a
  double clipped_high = 0.0;  //!< fraction of values above b
};

//! Applies Eq. 4. `what` names the input in error messages (a file name). Throws Error for
//! b <= a, values outside [0, 1], NaN, a sample whose percentile range collapses (no
//! contrast), or bad options. A grey image (or any image with `opts.colour`) passed as an
//! rvalue is mapped in place, without a copy.
image::Image enhanceContrast(image::Image img, const EnhanceOptions& opts, EnhanceReport* report = nullptr,
                             const std::string& what = "image");

//! The low and high percentiles (in percent) of the colour channels of `img` (alpha left
//! out), on a grid of 1/65535, which is exact for 8- and 16-bit data: the smallest value v
//! with at least p% of the values <= v. Values must lie in [0, 1].
ValueRange percentileRange(const image::Image& img, double low_percent, double high_percent);

}  // namespace shanshui::texsynth
