#include "shanshui/noise/gabor.h"

#include <cmath>
#include <numbers>

#include "shanshui/core/error.h"
#include "shanshui/core/random.h"

namespace shanshui::noise {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTruncation = 0.05;

double unit(std::uint64_t v) { return static_cast<double>(v >> 11) * (1.0 / 9007199254740992.0); }

// A per-cell seed: the cell coordinates and the global seed through SplitMix64, so nearby
// cells get unrelated streams (a bare Morton code would correlate them).
std::uint64_t cellSeed(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t h = splitMix64(seed ^ 0x9E3779B97F4A7C15ull);
  h = splitMix64(h ^ static_cast<std::uint64_t>(i));
  return splitMix64(h ^ (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4Full));
}

template <typename T>
void checkRange(const char* name, T v, T lo, T hi, bool lo_open) {
  if (!(lo_open ? v > lo : v >= lo) || !(v <= hi)) {
    throw makeError("gabor.", name, ": ", v, " is out of range; expected ", lo_open ? "(" : "[", lo, ", ", hi, "]");
  }
}

}  // namespace

void validate(const GaborOptions& o) {
  checkRange("K", o.K, 0.0, 1e6, true);
  checkRange("a", o.a, 0.0, 1e3, true);
  checkRange("F0", o.F0, 0.0, 1e3, false);
  if (!std::isfinite(o.omega0)) throw makeError("gabor.omega0: must be finite");
  checkRange("impulses", o.impulses, 1.0, 1024.0, false);
}

GaborNoise::GaborNoise(const GaborOptions& options) : o_(options) {
  validate(o_);
  radius_ = std::sqrt(-std::log(kTruncation) / kPi) / o_.a;
  density_ = o_.impulses / (kPi * radius_ * radius_);
  mean_per_cell_ = density_ * radius_ * radius_;
}

double GaborNoise::variance() const {
  return density_ * (1.0 / 3.0) * o_.K * o_.K / (4 * o_.a * o_.a) * (1 + std::exp(-2 * kPi * o_.F0 * o_.F0 / (o_.a * o_.a)));
}

double GaborNoise::spectrum(double fx, double fy) const {
  const double ux = o_.F0 * std::cos(o_.omega0), uy = o_.F0 * std::sin(o_.omega0);
  const double a2 = o_.a * o_.a;
  const double g = o_.K / (2 * a2) *
                   (std::exp(-kPi * ((fx - ux) * (fx - ux) + (fy - uy) * (fy - uy)) / a2) +
                    std::exp(-kPi * ((fx + ux) * (fx + ux) + (fy + uy) * (fy + uy)) / a2));
  return density_ * (1.0 / 3.0) * g * g;
}

double GaborNoise::operator()(double x, double y) const {
  const double r = radius_;
  const double ci = std::floor(x / r), cj = std::floor(y / r);
  const double a2 = o_.a * o_.a;
  double sum = 0;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const auto i = static_cast<std::int64_t>(ci) + di, j = static_cast<std::int64_t>(cj) + dj;
      const std::uint64_t s = cellSeed(i, j, o_.seed);
      // Poisson count by exponential inter-arrival times: exact, and no underflow for
      // large means (Knuth's product of uniforms would reach 0).
      std::uint64_t k = 0;
      int count = 0;
      for (double t = -std::log(1.0 - unit(streamValue(s, k++))); t < mean_per_cell_; ++count) {
        t += -std::log(1.0 - unit(streamValue(s, k++)));
      }
      for (int n = 0; n < count; ++n) {
        const double px = (static_cast<double>(i) + unit(streamValue(s, k++))) * r;
        const double py = (static_cast<double>(j) + unit(streamValue(s, k++))) * r;
        const double w = 2 * unit(streamValue(s, k++)) - 1;
        const double omega = o_.isotropic ? 2 * kPi * unit(streamValue(s, k++)) : o_.omega0;
        const double dx = x - px, dy = y - py, d2 = dx * dx + dy * dy;
        if (d2 >= r * r) continue;
        sum += w * o_.K * std::exp(-kPi * a2 * d2) * std::cos(2 * kPi * o_.F0 * (dx * std::cos(omega) + dy * std::sin(omega)));
      }
    }
  }
  return sum;
}

}  // namespace shanshui::noise
