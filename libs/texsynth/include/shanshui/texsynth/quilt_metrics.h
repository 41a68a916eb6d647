// Quality measures of a quilted texture (SPEC.md section 3, "Quality metrics"). All squared
// differences are summed over channels, with values in the sample's units.
#pragma once

#include <cstdint>

#include "shanshui/texsynth/quilting.h"

namespace shanshui::texsynth {

struct QuiltMetricsOptions {
  int patches = 256;       //!< random output patches for the coherence measure, [1, 100000]
  int patch_size = 8;      //!< their size, [2, block]; clamped to the sample size
  std::uint64_t seed = 7;  //!< where the patches are
  int threads = 0;         //!< 0 = one per hardware thread
};

struct QuiltMetrics {
  //! Seams are 4-neighbour output pairs whose sources are not neighbours in the sample. The
  //! seam error of such a pair is ‖out(q) − sample(src(p) + q − p)‖² + ‖out(p) − sample(src(q)
  //! + p − q)‖² (how far each side is from continuing the other; Kwatra et al.'s cost, squared).
  long long seam_edges = 0;
  double seam_error_per_edge = 0.0;
  double seam_error_per_overlap_pixel = 0.0;  //!< summed seam error / overlap pixels of the run
  //! Nearest-patch distance: per-pixel SSD between a random output patch and its best match
  //! anywhere in the sample; 0 = copied verbatim.
  double coherence_mean = 0.0;
  double coherence_max = 0.0;
  //! Source usage: how often each sample pixel appears in the output.
  double sample_coverage = 0.0;  //!< fraction of sample pixels used at least once
  double usage_cv = 0.0;         //!< standard deviation / mean of the use counts
  double usage_max_ratio = 0.0;  //!< most-used pixel's count / mean count
  //! Verbatim copies: 4-connected output regions copied from one place in the sample.
  double verbatim_copy_ratio = 0.0;  //!< largest region / output area
  double largest_copy_blocks = 0.0;  //!< largest region / block area
  double mean_region_pixels = 0.0;
  //! Seams across the wrap (last column next to the first, last row next to the first) and
  //! their summed error per wrap pair (continuous pairs count 0). A tileable texture has few
  //! such seams, cut like the others; otherwise the wrap is one long seam between unrelated
  //! pixels.
  long long wrap_seam_edges = 0;
  double wrap_seam_error = 0.0;
};

QuiltMetrics measureQuilt(const image::Image& sample, const QuiltResult& result, int block,
                          const QuiltMetricsOptions& opts = {});

}  // namespace shanshui::texsynth
