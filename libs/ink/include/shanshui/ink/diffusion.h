// Empirical ink diffusion in image space (seed 001, Eqs. 6-8; SPEC.md section 9): the CPU
// reference implementation, written for clarity and used as the oracle of the GPU pass.
//
// The model works on an ink field I ≥ 0 (0 = bare paper) and has three regions:
//  - stroke region S: pixels with I > threshold;
//  - main diffusion region: rings 1..d around S (4-neighbour steps). Each ring pixel takes
//    I_p = f · mean(I of its 4-neighbours on the previous ring), kept if larger than its
//    own ink. The paper's printed A_p = 1 − mean(A_i·f) oscillates; the intended geometric
//    decay is what is implemented (SPEC.md). Opacity f^r never increases with the ring r;
//  - boundary diffusion: n iterations in which every pixel outside S absorbs ink from its
//    8-neighbours in proportion to their ink above the residual I_r, at most I_p·a/n per
//    iteration (a = the canvas absorbency at the pixel); a donor loses exactly what its
//    receivers gain and never drops below I_r. Each iteration is an order-independent
//    gather from the previous iteration's values. Pixels outside the image are absent.
#pragma once

#include <cstdint>

#include "shanshui/core/range.h"
#include "shanshui/image/image.h"

namespace shanshui::ink {

// Ranges of the options below; the scene's parameter description (libs/scene) and
// validate() both read these, so the CPU reference and the scene agree.
inline constexpr Range<int> kRingStepsRange{0, 256};
inline constexpr Range<double> kAttenuationRange{0.0, 1.0};
inline constexpr Range<double> kAbsorbRange{0.0, 1e3};
inline constexpr Range<double> kResidualRange{0.0, 1.0};
inline constexpr Range<int> kIterationsRange{0, 1000};
inline constexpr Range<double> kThresholdRange{0.0, 1.0};

//! Defaults chosen on the sample scene: a soft bleed around lines and dark strokes.
struct DiffusionOptions {
  int ring_steps = 3;        //!< d, main diffusion distance in pixels, kRingStepsRange
  double attenuation = 0.6;  //!< f, ink kept per ring, kAttenuationRange
  double absorb = 0.3;       //!< I_p, ink a pixel can absorb over the n iterations, kAbsorbRange
  double residual = 0.1;     //!< I_r, ink a donor keeps, kResidualRange
  int iterations = 5;        //!< n, boundary diffusion iterations, kIterationsRange
  double threshold = 0.8;    //!< ink above which a pixel is a stroke, kThresholdRange
};

//! Checks the ranges; throws Error naming the parameter, the value and the range.
void validate(const DiffusionOptions& options);

//! An ink field: one float per pixel, row-major, row 0 at the top.
struct InkField {
  int width = 0;
  int height = 0;
  std::vector<double> ink;
  double at(int x, int y) const { return ink[static_cast<std::size_t>(y) * width + x]; }
  double total() const;
};

//! Ink of a rendered picture: I = clamp(1 − lum(c) / lum(paper), 0, 1), so the paper is 0.
InkField inkFromImage(const image::Image& rgb, const double paper_rgb[3]);

//! The picture with the ink change painted in: c − paper · (I_after − I_before), clamped to
//! [0, 1]; an unchanged pixel keeps its colour exactly.
image::Image applyInk(const image::Image& rgb, const InkField& before, const InkField& after,
                      const double paper_rgb[3]);

//! Main diffusion region by the plain ring-by-ring iteration (d sweeps of the image).
//! `ring` (optional) receives each pixel's ring index: 0 in S, 1..d in the region, −1 else.
InkField mainDiffusionIterative(const InkField& in, const DiffusionOptions& o, std::vector<int>* ring = nullptr);

//! The same region from an exact city-block distance transform (two separable sweeps per
//! axis, independent of d): ring = distance to S, ink = f^ring · (ink of a nearest stroke
//! pixel). Equal to the iteration wherever the nearest stroke pixels of a ring pixel carry
//! the same ink (always for a uniform stroke); elsewhere both are f^r-weighted means of
//! the ink of stroke pixels at distance r, so they differ by at most
//! f^r · (max − min of that ink) — the tests check this bound.
InkField mainDiffusionDistance(const InkField& in, const DiffusionOptions& o, std::vector<int>* ring = nullptr);

//! Boundary diffusion: n gather iterations. `absorbency` is one value in [0, 1] per pixel
//! (empty: 1 everywhere); `stroke` marks S (pixels that do not absorb).
InkField boundaryDiffusion(const InkField& in, const std::vector<float>& absorbency, const std::vector<bool>& stroke,
                           const DiffusionOptions& o);

//! The whole model: main region (distance transform), then boundary diffusion.
InkField diffuseInk(const InkField& in, const std::vector<float>& absorbency, const DiffusionOptions& o);

}  // namespace shanshui::ink
