#include "shanshui/noise/gabor.h"

#include <cmath>
#include <numbers>

#include "shanshui/core/error.h"

namespace shanshui::noise {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTruncation = 0.05;

double unit(std::uint32_t v) {
  return static_cast<double>(v >> 8) * (1.0 / 16777216.0);
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
  checkRange("impulses", o.impulses, kImpulsesRange.lo, kImpulsesRange.hi, kImpulsesRange.lo_open);
}

GaborNoise::GaborNoise(const GaborOptions& options) : o_(options) {
  validate(o_);
  radius_ = std::sqrt(-std::log(kTruncation) / kPi) / o_.a;
  density_ = o_.impulses / (kPi * radius_ * radius_);
  mean_per_cell_ = density_ * radius_ * radius_;
}

double GaborNoise::variance() const {
  return density_ * (1.0 / 3.0) * o_.K * o_.K / (4 * o_.a * o_.a) *
         (1 + std::exp(-2 * kPi * o_.F0 * o_.F0 / (o_.a * o_.a)));
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
  const std::uint32_t seed = noiseSeed32(o_.seed);
  double sum = 0;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      const auto i = static_cast<std::int32_t>(ci) + di, j = static_cast<std::int32_t>(cj) + dj;
      const std::uint32_t s = noiseCellSeed(i, j, seed);
      std::uint32_t k = 0;
      const int count = impulseCount(mean_per_cell_, unit(noiseStream(s, k++)));
      for (int n = 0; n < count; ++n) {
        const double px = (i + unit(noiseStream(s, k++))) * r;
        const double py = (j + unit(noiseStream(s, k++))) * r;
        const double w = 2 * unit(noiseStream(s, k++)) - 1;
        const double omega = o_.isotropic ? 2 * kPi * unit(noiseStream(s, k++)) : o_.omega0;
        const double dx = x - px, dy = y - py, d2 = dx * dx + dy * dy;
        if (d2 >= r * r) continue;
        sum += w * o_.K * std::exp(-kPi * a2 * d2) *
               std::cos(2 * kPi * o_.F0 * (dx * std::cos(omega) + dy * std::sin(omega)));
      }
    }
  }
  return sum;
}

std::uint32_t noiseHash(std::uint32_t v) {
  const std::uint32_t state = v * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

std::uint32_t noiseSeed32(std::uint64_t seed) {
  return noiseHash(static_cast<std::uint32_t>(seed) ^ noiseHash(static_cast<std::uint32_t>(seed >> 32)));
}

std::uint32_t noiseCellSeed(std::int32_t i, std::int32_t j, std::uint32_t seed) {
  return noiseHash(noiseHash(seed + static_cast<std::uint32_t>(i)) + static_cast<std::uint32_t>(j));
}

std::uint32_t noiseStream(std::uint32_t s, std::uint32_t k) {
  return noiseHash(s + 0x9E3779B9u * k);
}

int impulseCount(double mean, double u) {
  const double whole = std::floor(mean);
  return static_cast<int>(whole) + (u < mean - whole ? 1 : 0);
}

}  // namespace shanshui::noise
