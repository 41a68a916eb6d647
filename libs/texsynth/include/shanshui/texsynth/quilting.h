// Texture synthesis by image quilting (Efros & Freeman 2001; SPEC.md section 3), with the
// minimum error boundary cut or graph-cut seams (Kwatra et al. 2003) and tileable output.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "shanshui/image/image.h"
#include "shanshui/texsynth/overlap_search.h"
#include "shanshui/texsynth/seam.h"

namespace shanshui::texsynth {

struct QuiltOptions {
  int width = 512;         //!< output width, >= block
  int height = 512;        //!< output height, >= block
  int block = 48;          //!< B, block size in pixels, [3, min(sample width, height)]
  int overlap = -1;        //!< O, [1, B − 1]; −1 = round(B / 6), at least 1
  double tolerance = 0.1;  //!< candidates within (1 + tol)·min error, [0, 1e9]
  //! Absolute floor of the candidate threshold per overlap pixel and channel, [0, 1]: keeps
  //! blank paper (all errors near 0) from leaving a single candidate.
  double error_floor = 1e-4;
  std::uint64_t seed = 1;  //!< same seed, same output, whatever the thread count
  SeamMode seam = SeamMode::Cut;
  SearchMode search = SearchMode::Fft;
  bool tileable = false;  //!< wrap-around overlaps so the output tiles seamlessly
  int threads = 0;        //!< worker threads; 0 = one per hardware thread
  //! Also run the exhaustive search for every block and record how the chosen error compares
  //! with its minimum (slow; for benchmarks).
  bool audit = false;
  //! Called after each wave of blocks with (blocks done, blocks in total).
  std::function<void(int, int)> progress;

  //! The overlap actually used (resolves −1).
  int resolvedOverlap() const;
};

//! What one run did and how good the choices were.
struct QuiltStats {
  double seconds = 0.0;
  int blocks = 0;
  int blocks_x = 0, blocks_y = 0;
  int waves = 0;  //!< groups of independent blocks searched in parallel
  int threads = 1;
  double mean_candidates = 0.0;  //!< candidates per block with an overlap
  long long overlap_pixels = 0;  //!< summed over all blocks
  //! Overlap error of the chosen blocks (SSD summed over channels) per overlap pixel.
  double overlap_error_per_pixel = 0.0;
  //! With audit: mean over blocks of chosen error / exhaustive minimum (floored as in the
  //! candidate rule); 1 is the best any search can do. −1 without audit.
  double search_error_ratio = -1.0;
  //! With audit: fraction of blocks whose choice the exhaustive search would not have
  //! allowed (error above its candidate threshold); 0 for an exact search. −1 without audit.
  double search_rule_violations = -1.0;
  double audit_seconds = 0.0;  //!< CPU time spent in the audit (part of `seconds`)
};

struct QuiltResult {
  image::Image image;  //!< width × height, the sample's channels
  //! For every output pixel, the index y·sample_width + x of the sample pixel it shows.
  std::vector<std::int32_t> source;
  QuiltStats stats;
};

//! The candidate rule (SPEC.md section 3, step 3): windows with overlap error at most
//! (1 + tolerance)·max(min_error, error_floor·values), where `values` = overlap pixels ×
//! channels, plus a slack of 1e-9 of the error scale so that exact ties (two-level samples
//! have integer errors) are kept by the FFT search as by the exhaustive one.
double candidateThreshold(double min_error, long long values, const QuiltOptions& opts);

//! Synthesises `opts.width × opts.height` from `sample`. `what` names the sample in errors.
//! Throws Error for bad options (naming the parameter, the value and the range) or a sample
//! smaller than a block.
QuiltResult quilt(const image::Image& sample, const QuiltOptions& opts, const std::string& what = "sample");

//! Checks the options against a sample of the given size; throws Error like quilt().
void validate(const QuiltOptions& opts, int sample_width, int sample_height, const std::string& what = "sample");

}  // namespace shanshui::texsynth
