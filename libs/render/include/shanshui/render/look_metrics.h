// What a painter would look at, as numbers (issue 22 item 7): how much of the sheet is
// bare paper, how wide the dark strokes are, whether far land is lighter than near land,
// and whether a straight cut edge shows. They back the eye; they do not replace it.
#pragma once

#include <utility>

#include <glm/glm.hpp>

#include "shanshui/image/image.h"

namespace shanshui::render {

struct LookStatistics {
  //! Share of the picture's pixels within paper tone: ink below 0.1, where ink is
  //! 1 − luminance / the paper's luminance (clamped to [0, 1]).
  double paper_share = 0.0;
  //! Mean width of the dark marks (ink above 0.5): their area over the length of their
  //! skeleton (zhangSuenSkeleton), in pixels; 0 when there are none.
  double dark_width_px = 0.0;
  double dark_share = 0.0;  //!< share of the picture's pixels that are dark marks
  //! Mean ink of the subject's top third of rows over its bottom third: far over near for a
  //! view from above the land. The subject is the mask where given, else the pixels
  //! carrying ink above 0.1; 0 when the bottom third carries none.
  double far_near_ink = 0.0;
  //! Longest straight segment of the ink's edges (Canny, probabilistic Hough with gaps of
  //! at most 2 pixels), as a fraction of the picture's width.
  double longest_straight = 0.0;
  //! Brushwork (issue 44): distinct dark marks per megapixel, counted on the picture resampled
  //! to one megapixel (area averaging), a mark being an 8-connected region of ink above 1/3
  //! of at least 3 pixels; two real ink landscapes have about 1,600.
  double marks_per_mp = 0.0;
  //! The spread of the marks' sizes: the interquartile range of log2 of their areas (pixels
  //! at one megapixel); 0 with fewer than four marks. The real landscapes: about 2.6.
  double mark_size_spread = 0.0;
};

//! The marks of the picture as LookStatistics counts them: marks per megapixel and the
//! interquartile range of log2 of their areas, from a one-channel ink image in [0, 1]
//! (1 = full black) of any size.
std::pair<double, double> darkMarks(const image::Image& ink);

//! The statistics of an RGB picture (values in [0, 1], row 0 at the top) painted on
//! `paper`. `subject`, when given, is one channel of the picture's size, > 0.5 where the
//! scene's surfaces are.
LookStatistics lookStatistics(const image::Image& rgb, const glm::dvec3& paper, const image::Image* subject = nullptr);

//! Zhang–Suen thinning of a mask (one channel, set where > 0.5): 1 on its skeleton, 0
//! elsewhere; the pixels OpenCV's cv::ximgproc::thinning(THINNING_ZHANGSUEN) gives. The
//! outermost rows and columns are never thinned, as there.
image::Image zhangSuenSkeleton(const image::Image& mask);

}  // namespace shanshui::render
