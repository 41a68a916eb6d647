// Where a new quilting block replaces what is already there: the boundary between the old
// and the new pixels inside the block's overlap (SPEC.md section 3, steps 4 and 5).
#pragma once

#include <opencv2/core.hpp>

#include "shanshui/image/image.h"

namespace shanshui::texsynth {

enum class SeamMode {
  Cut,       //!< minimum error boundary cut per overlap strip (Efros & Freeman 2001)
  GraphCut,  //!< minimum cut over the whole overlap (Kwatra et al. 2003), Boykov–Kolmogorov max-flow
  None,      //!< the new block replaces everything in its footprint
};

const char* seamModeName(SeamMode mode);

//! Overlap strips of a block footprint: how many columns (rows) on each side are filled
//! for every row (column). Quilting in raster order fills exactly such strips.
struct OverlapStrips {
  int left = 0, right = 0, top = 0, bottom = 0;
};
OverlapStrips overlapStrips(const cv::Mat& filled);

//! The pixels of a B×B block that take the new patch: CV_8U, 1 = new, 0 = keep old.
//! `old` holds what is in the footprint now (meaningful where `filled` != 0), `patch` the
//! candidate; both B×B with the same channels. Pixels not yet filled are always new.
//! Every filled pixel must lie in one of the strips overlapStrips() finds.
cv::Mat seamMask(const image::Image& old, const image::Image& patch, const cv::Mat& filled, SeamMode mode);

//! The graph-cut labelling alone: nodes are the filled pixels, 4-neighbour edge weights
//! ‖old(s) − new(s)‖ + ‖old(t) − new(t)‖; filled pixels on a block side that has a strip
//! are tied to the old patch, filled pixels next to an unfilled one to the new patch.
cv::Mat graphCutMask(const image::Image& old, const image::Image& patch, const cv::Mat& filled);

//! Per-pixel squared difference summed over channels, CV_64F (0 where not filled).
cv::Mat overlapDifference(const image::Image& old, const image::Image& patch, const cv::Mat& filled);

}  // namespace shanshui::texsynth
