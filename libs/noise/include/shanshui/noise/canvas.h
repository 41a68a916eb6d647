// The paper canvas's noise kernel (seed 001 Eqs. 9-17, SPEC.md section 8) and its
// statistics: one kernel per impulse, rice paper (a Perlin-textured Gaussian) or silk (a
// Gabor kernel mixed with its twin at ω + 90°, the weft). shaders/canvas/canvas_kernel.glsl is the
// GLSL twin; the canvas pass divides by canvasSigma() so the paper has unit variance.
#pragma once

namespace shanshui::noise {

struct CanvasNoiseOptions {
  bool silk = false;              //!< else rice paper
  double radius = 6.0;            //!< r, truncation radius (length units, pixels for the canvas)
  double F0 = 0.1;                //!< silk: cycles per length unit
  double omega0 = 0.0;            //!< silk: radians
  bool isotropic = false;         //!< silk: random orientation per impulse
  double mix = 0.5;               //!< silk: weight of the twin across the threads (the weft)
  double perlin_frequency = 1.5;  //!< rice paper: Perlin cycles per radius
  double impulses = 64.0;         //!< N′
};

//! a = sqrt(−ln 0.05 / π) / r: the Gaussian is 5 % at the radius.
double canvasBandwidth(const CanvasNoiseOptions& o);

//! The kernel at offset (dx, dy) from its impulse, for the impulse's randoms e0, e1, e2
//! in [0, 1) (silk: e0 the orientation when isotropic; rice paper: the Perlin offset);
//! 0 beyond the radius. Unit amplitude, weight not included.
double canvasKernel(const CanvasNoiseOptions& o, double dx, double dy, double e0, double e1, double e2);

//! The noise's standard deviation: sqrt(λ E[w²] E[∫ k²]) with λ = N′ / (π r²), E[w²] = 1/3,
//! and the kernel's energy averaged over its randoms (quadrature over the disc; for rice
//! paper the Perlin noise's mean square times the window's energy).
double canvasSigma(const CanvasNoiseOptions& o);

//! E[perlin(p)²] over p uniform in one period (measured once, to 0.3 %).
double perlinMeanSquare();

}  // namespace shanshui::noise
