#include "shanshui/strokes/brush.h"

#include <algorithm>
#include <cmath>

#include "shanshui/core/error.h"

namespace shanshui::strokes {
namespace {

// A hash to [0, 1) for the seeded variation (splitmix64).
double unit(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) / 9007199254740992.0;
}

// 0 → 1 → 0 with the peak at `peak` in (0, 1), smooth (a sine quarter each side).
double rise(double t, double peak) {
  if (t <= peak) return std::sin(0.5 * M_PI * t / peak);
  return std::sin(0.5 * M_PI * (1.0 - t) / (1.0 - peak));
}

}  // namespace

StrokeStyle styleFor(StrokeStyle style, double length, const BrushOptions& o) {
  if (style != StrokeStyle::Mixed) return style;
  if (length >= o.mixed_long_px) return StrokeStyle::Liuye;
  if (length >= o.mixed_short_px) return StrokeStyle::Zaohe;
  return StrokeStyle::Jianbi;
}

double pressure(StrokeStyle style, double t, double length, std::uint64_t seed, const BrushOptions& o) {
  t = std::clamp(t, 0.0, 1.0);
  switch (styleFor(style, length, o)) {
    case StrokeStyle::None:
      return 0.0;
    case StrokeStyle::Qinxian:
      return 1.0;
    case StrokeStyle::Liuye:
      // The turn from pressing to lifting falls between 30 % and 70 % of the stroke.
      return rise(t, 0.3 + 0.4 * unit(seed));
    case StrokeStyle::Zaohe: {
      const int beats = std::max(1, static_cast<int>(std::lround(length / o.zaohe_beat_px)));
      const double u = t * beats - std::floor(std::min(t * beats, beats - 1e-12));
      return rise(u, 0.5);
    }
    case StrokeStyle::Jianbi:
    case StrokeStyle::Zhuye:
      // Pressed at once, lifted quickly: full for the first tenth, then a steep fall.
      return t < 0.1 ? 1.0 : std::pow(1.0 - (t - 0.1) / 0.9, 2.0);
    case StrokeStyle::Mixed:
      break;
  }
  return 0.0;
}

std::vector<StripVertex> strokeStrip(const std::vector<glm::dvec2>& path, StrokeStyle style, std::uint64_t seed,
                                     const BrushOptions& o) {
  if (!(o.width_px > 0.0 && o.width_px <= 256.0)) throw makeError("brush width ", o.width_px, " px; expected (0, 256]");
  if (!(o.min_pressure >= 0.0 && o.min_pressure <= 1.0)) {
    throw makeError("brush minimum pressure ", o.min_pressure, "; expected [0, 1]");
  }
  std::vector<StripVertex> strip;
  if (path.size() < 2 || style == StrokeStyle::None) return strip;
  std::vector<double> along(path.size(), 0.0);
  for (std::size_t i = 1; i < path.size(); ++i) along[i] = along[i - 1] + glm::length(path[i] - path[i - 1]);
  const double length = along.back();
  if (!(length > 0.0)) return strip;
  const StrokeStyle drawn = styleFor(style, length, o);
  // Right edge offset -right·w, left edge +left·w from the path.
  const double right = drawn == StrokeStyle::Zhuye ? 0.2 : 0.5, left = 1.0 - right;
  strip.reserve(2 * path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    // The normal of the mean of the neighbouring directions.
    const glm::dvec2 before = i > 0 ? path[i] - path[i - 1] : path[1] - path[0];
    const glm::dvec2 after = i + 1 < path.size() ? path[i + 1] - path[i] : before;
    glm::dvec2 dir = (glm::length(before) > 0 ? glm::normalize(before) : glm::dvec2(0.0)) +
                     (glm::length(after) > 0 ? glm::normalize(after) : glm::dvec2(0.0));
    if (glm::length(dir) == 0.0) dir = after;
    dir = glm::length(dir) > 0 ? glm::normalize(dir) : glm::dvec2(1, 0);
    const glm::dvec2 normal(-dir.y, dir.x);
    const double p = pressure(drawn, along[i] / length, length, seed, o);
    const double width = o.width_px * (o.min_pressure + (1.0 - o.min_pressure) * p);
    const auto a = static_cast<float>(along[i]), pf = static_cast<float>(p);
    strip.push_back({path[i] - normal * (right * width), a, -1.0f, pf});
    strip.push_back({path[i] + normal * (left * width), a, 1.0f, pf});
  }
  return strip;
}

double lengthInk(double length_px, double short_px) {
  if (!(short_px > 0.0)) return 1.0;
  const double t = std::clamp((length_px - short_px) / (2.0 * short_px), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace shanshui::strokes
