#include "shanshui/noise/canvas.h"

#include <cmath>
#include <numbers>

#include "shanshui/noise/perlin.h"

namespace shanshui::noise {

namespace {
constexpr double kPi = std::numbers::pi;

double gabor(double dx, double dy, double a, double F0, double omega) {
  return std::exp(-kPi * a * a * (dx * dx + dy * dy)) *
         std::cos(2 * kPi * F0 * (dx * std::cos(omega) + dy * std::sin(omega)));
}
}  // namespace

double canvasBandwidth(const CanvasNoiseOptions& o) {
  return std::sqrt(-std::log(0.05) / kPi) / o.radius;
}

double canvasKernel(const CanvasNoiseOptions& o, double dx, double dy, double e0, double e1, double e2) {
  const double r = o.radius;
  if (dx * dx + dy * dy >= r * r) return 0.0;
  const double a = canvasBandwidth(o);
  if (o.silk) {
    const double omega = o.isotropic ? 2 * kPi * e0 : o.omega0;
    // The twin at swapped coordinates with −ω runs at ω + 90°: the weft across the warp
    // (with ω itself it would run at 90° − ω, along the warp at 45°).
    return (1 - o.mix) * gabor(dx, dy, a, o.F0, omega) + o.mix * gabor(dy, dx, a, o.F0, -omega);
  }
  const double f = o.perlin_frequency / r;
  return std::exp(-kPi * a * a * (dx * dx + dy * dy)) * perlin(dx * f + 256 * e0, dy * f + 256 * e1, 256 * e2);
}

double perlinMeanSquare() {
  // A 3-D Kronecker (R3) sequence spreads the points evenly through the 256³ period.
  static const double value = [] {
    const double g = 1.2207440846057596;  // the plastic-like root of x⁴ = x + 1
    const double alpha[3] = {1 / g, 1 / (g * g), 1 / (g * g * g)};
    const int n = 400000;
    double sum = 0;
    for (int i = 1; i <= n; ++i) {
      double p[3];
      for (int c = 0; c < 3; ++c) p[c] = 256 * std::fmod(0.5 + alpha[c] * i, 1.0);
      const double v = perlin(p[0], p[1], p[2]);
      sum += v * v;
    }
    return sum / n;
  }();
  return value;
}

double canvasSigma(const CanvasNoiseOptions& o) {
  const double r = o.radius, a = canvasBandwidth(o);
  double energy = 0;
  if (!o.silk) {
    // ∫ e^(−2π a² ρ²) over the disc, times the Perlin mean square (the offset is uniform).
    energy = (1 - 0.05 * 0.05) / (2 * a * a) * perlinMeanSquare();
  } else {
    // Midpoint quadrature over the disc, 128² cells; orientations averaged when isotropic.
    const int n = 128, orientations = o.isotropic ? 64 : 1;
    const double h = 2 * r / n;
    for (int k = 0; k < orientations; ++k) {
      const double e0 = (k + 0.5) / orientations;
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const double v = canvasKernel(o, -r + (i + 0.5) * h, -r + (j + 0.5) * h, e0, 0, 0);
          energy += v * v * h * h;
        }
    }
    energy /= orientations;
  }
  const double density = o.impulses / (kPi * r * r);
  return std::sqrt(density * energy / 3.0);
}

}  // namespace shanshui::noise
