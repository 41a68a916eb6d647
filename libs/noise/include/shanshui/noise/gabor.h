// Sparse-convolution Gabor noise (Lagae et al. 2009): the silk canvas of seed 001, Eqs.
// 9-14 (SPEC.md section 8, with the corrected variance). CPU reference; shaders/ carries
// the GLSL version (issue 7).
#pragma once

#include <cstdint>

#include "shanshui/core/range.h"

namespace shanshui::noise {

//! N′, expected impulses per kernel disc, for the Gabor noise and the canvas.
inline constexpr Range<double> kImpulsesRange{1.0, 1024.0};

struct GaborOptions {
  double K = 1.0;                      //!< kernel amplitude, (0, 1e6]
  double a = 0.05;                     //!< Gaussian bandwidth (1 / length), (0, 1e3]
  double F0 = 0.0625;                  //!< harmonic frequency (cycles / length), [0, 1e3]
  double omega0 = 0.7853981633974483;  //!< orientation, radians (anisotropic noise)
  bool isotropic = false;              //!< each impulse gets a random orientation instead of omega0
  double impulses = 64.0;              //!< N′, expected impulses per kernel disc, kImpulsesRange
  std::uint64_t seed = 1;
};

//! Checks the ranges; throws Error naming the parameter, the value and the range.
void validate(const GaborOptions& options);

class GaborNoise {
 public:
  explicit GaborNoise(const GaborOptions& options);

  //! The noise at (x, y): Σ over impulses in the 3×3 cells around the point of
  //! w_i · K e^(−π a² |d|²) cos(2π F0 (d_x cos ω_i + d_y sin ω_i)), d = (x, y) − x_i, for
  //! |d| below the truncation radius. Cells have the size of that radius; each cell's
  //! impulses (impulseCount() of mean λ r², uniform positions, weights U[−1, 1]) come from
  //! a stream seeded by a hash of the cell and the seed, so the noise is the same wherever
  //! and in whatever order it is evaluated. shaders/common/noise_gabor.glsl draws the same
  //! impulses from the same 32-bit hashes.
  double operator()(double x, double y) const;

  //! Truncation radius r = sqrt(−ln 0.05 / π) / a: the envelope is 5 % there.
  double radius() const { return radius_; }
  //! Impulse density λ = N′ / (π r²).
  double density() const { return density_; }
  //! σ² = λ E[w²] K² / (4 a²) (1 + e^(−2π F0² / a²)), E[w²] = 1/3 (untruncated kernel).
  double variance() const;
  //! The analytic power spectrum at frequency (fx, fy) (cycles / length), for the
  //! anisotropic noise: λ E[w²] |Ĝ|², Ĝ = K/(2a²) (e^(−π|f − f0|²/a²) + e^(−π|f + f0|²/a²)).
  double spectrum(double fx, double fy) const;

 private:
  GaborOptions o_;
  double radius_, density_, mean_per_cell_;
};

// The random streams shared with the shaders: 32-bit so GLSL reproduces them exactly.
// A uniform in [0, 1) is the top 24 bits of a hash, exact in float and double.

//! PCG's output permutation of one 32-bit word (Jarzynski and Olano 2020).
std::uint32_t noiseHash(std::uint32_t v);
//! A 64-bit scene seed folded to the 32 bits the shaders take.
std::uint32_t noiseSeed32(std::uint64_t seed);
//! The seed of cell (i, j).
std::uint32_t noiseCellSeed(std::int32_t i, std::int32_t j, std::uint32_t seed);
//! Value k of the stream with seed s.
std::uint32_t noiseStream(std::uint32_t s, std::uint32_t k);
//! Impulses in a cell or triangle of expected count `mean`: ⌊mean⌋, plus one when the
//! uniform u falls below the fraction. The mean is exact, and since the weights have zero
//! mean the noise's variance and spectrum depend on nothing else (a Poisson count would
//! only add clumping); unlike a Poisson draw it needs no logarithms that float and double
//! would round differently.
int impulseCount(double mean, double u);

}  // namespace shanshui::noise
