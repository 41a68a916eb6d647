#include "shanshui/ink/diffusion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shanshui/core/error.h"

namespace shanshui::ink {

namespace {

template <typename T>
void checkRange(const char* name, T value, Range<T> range) {
  if (!range.contains(value)) {
    throw makeError("diffusion.", name, ": ", value, " is out of range; expected ", range.text());
  }
}

double luminance(const float* c) {
  return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

std::vector<bool> strokeMask(const InkField& in, double threshold) {
  std::vector<bool> s(in.ink.size());
  for (std::size_t i = 0; i < s.size(); ++i) s[i] = in.ink[i] > threshold;
  return s;
}

}  // namespace

void validate(const DiffusionOptions& o) {
  checkRange("ring_steps", o.ring_steps, kRingStepsRange);
  checkRange("attenuation", o.attenuation, kAttenuationRange);
  checkRange("absorb", o.absorb, kAbsorbRange);
  checkRange("residual", o.residual, kResidualRange);
  checkRange("iterations", o.iterations, kIterationsRange);
  checkRange("threshold", o.threshold, kThresholdRange);
}

double InkField::total() const {
  double sum = 0;
  for (double v : ink) sum += v;
  return sum;
}

InkField inkFromImage(const image::Image& rgb, const double paper[3]) {
  if (rgb.channels < 3) throw makeError("ink diffusion needs an RGB image, not ", rgb.channels, " channel(s)");
  const float p[3] = {static_cast<float>(paper[0]), static_cast<float>(paper[1]), static_cast<float>(paper[2])};
  const double paper_lum = std::max(luminance(p), 1e-6);
  InkField f{rgb.width, rgb.height, std::vector<double>(static_cast<std::size_t>(rgb.width) * rgb.height)};
  for (int y = 0; y < rgb.height; ++y) {
    for (int x = 0; x < rgb.width; ++x) {
      f.ink[static_cast<std::size_t>(y) * rgb.width + x] =
          std::clamp(1.0 - luminance(&rgb.pixels[rgb.index(x, y)]) / paper_lum, 0.0, 1.0);
    }
  }
  return f;
}

image::Image applyInk(const image::Image& rgb, const InkField& before, const InkField& after, const double paper[3]) {
  SHANSHUI_CHECK_EQ(before.ink.size(), after.ink.size());
  image::Image out = rgb;
  for (int y = 0; y < rgb.height; ++y) {
    for (int x = 0; x < rgb.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * rgb.width + x;
      const double change = after.ink[i] - before.ink[i];
      if (change == 0.0) continue;
      for (int c = 0; c < 3; ++c) {
        out.at(x, y, c) = static_cast<float>(std::clamp(rgb.at(x, y, c) - paper[c] * change, 0.0, 1.0));
      }
    }
  }
  return out;
}

InkField mainDiffusionIterative(const InkField& in, const DiffusionOptions& o, std::vector<int>* ring_out) {
  validate(o);
  const int w = in.width, h = in.height;
  std::vector<int> ring(in.ink.size(), -1);
  const std::vector<bool> stroke = strokeMask(in, o.threshold);
  std::vector<double> value(in.ink.size(), 0.0);  // ink carried by the rings
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (stroke[i]) ring[i] = 0, value[i] = in.ink[i];
  }
  InkField out = in;
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int r = 1; r <= o.ring_steps; ++r) {
    bool grew = false;
    std::vector<std::size_t> fresh;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        if (ring[i] != -1) continue;
        double sum = 0;
        int count = 0;
        for (int k = 0; k < 4; ++k) {
          const int nx = x + dx[k], ny = y + dy[k];
          if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;  // outside is absent
          const std::size_t j = static_cast<std::size_t>(ny) * w + nx;
          if (ring[j] == r - 1) sum += value[j], ++count;
        }
        if (count == 0) continue;
        value[i] = o.attenuation * sum / count;
        fresh.push_back(i);
        grew = true;
      }
    }
    for (std::size_t i : fresh) {
      ring[i] = r;
      out.ink[i] = std::max(out.ink[i], value[i]);
    }
    if (!grew) break;
  }
  if (ring_out) *ring_out = std::move(ring);
  return out;
}

InkField mainDiffusionDistance(const InkField& in, const DiffusionOptions& o, std::vector<int>* ring_out) {
  validate(o);
  const int w = in.width, h = in.height;
  const std::vector<bool> stroke = strokeMask(in, o.threshold);
  constexpr int kFar = std::numeric_limits<int>::max() / 4;
  // City-block distance is separable: distance along the row to the nearest stroke pixel
  // (two sweeps), then the minimum over rows of row distance + |dy| (two sweeps per
  // column). The source ink travels with the distance; ties keep the larger ink.
  std::vector<int> row_d(in.ink.size(), kFar);
  std::vector<double> row_v(in.ink.size(), 0.0);
  for (int y = 0; y < h; ++y) {
    const std::size_t base = static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      const std::size_t i = base + x;
      if (stroke[i])
        row_d[i] = 0, row_v[i] = in.ink[i];
      else if (x > 0 && row_d[i - 1] < kFar)
        row_d[i] = row_d[i - 1] + 1, row_v[i] = row_v[i - 1];
    }
    for (int x = w - 2; x >= 0; --x) {
      const std::size_t i = base + x;
      if (row_d[i + 1] >= kFar) continue;
      const int d = row_d[i + 1] + 1;
      if (d < row_d[i] || (d == row_d[i] && row_v[i + 1] > row_v[i])) row_d[i] = d, row_v[i] = row_v[i + 1];
    }
  }
  std::vector<int> dist = row_d;
  std::vector<double> src = row_v;
  for (int x = 0; x < w; ++x) {
    for (int pass = 0; pass < 2; ++pass) {
      const int step = pass == 0 ? 1 : -1;
      for (int y = pass == 0 ? 1 : h - 2; y >= 0 && y < h; y += step) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x, j = static_cast<std::size_t>(y - step) * w + x;
        if (dist[j] >= kFar) continue;
        const int d = dist[j] + 1;
        if (d < dist[i] || (d == dist[i] && src[j] > src[i])) dist[i] = d, src[i] = src[j];
      }
    }
  }
  InkField out = in;
  std::vector<int> ring(in.ink.size(), -1);
  for (std::size_t i = 0; i < ring.size(); ++i) {
    if (dist[i] > o.ring_steps) continue;
    ring[i] = dist[i];
    if (dist[i] > 0) out.ink[i] = std::max(out.ink[i], std::pow(o.attenuation, dist[i]) * src[i]);
  }
  if (ring_out) *ring_out = std::move(ring);
  return out;
}

InkField boundaryDiffusion(const InkField& in, const std::vector<float>& absorbency, const std::vector<bool>& stroke,
                           const DiffusionOptions& o) {
  validate(o);
  const int w = in.width, h = in.height;
  const std::size_t n = in.ink.size();
  SHANSHUI_CHECK(absorbency.empty() || absorbency.size() == n);
  SHANSHUI_CHECK_EQ(stroke.size(), n);
  InkField cur = in;
  if (o.iterations == 0 || n == 0) return cur;
  std::vector<double> capacity(n);  // ink a receiver takes per iteration
  for (std::size_t i = 0; i < n; ++i) {
    const double a = absorbency.empty() ? 1.0 : std::clamp(static_cast<double>(absorbency[i]), 0.0, 1.0);
    capacity[i] = stroke[i] ? 0.0 : o.absorb * a / o.iterations;
  }
  std::vector<double> demand(n), supply(n);
  auto forNeighbours = [&](int x, int y, auto&& fn) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;  // outside is absent
        fn(static_cast<std::size_t>(ny) * w + nx);
      }
  };
  for (int it = 0; it < o.iterations; ++it) {
    const std::vector<double>& I = cur.ink;
    auto excess = [&](std::size_t i) { return std::max(0.0, I[i] - o.residual); };
    // 1. Each receiver p asks neighbour i for capacity_p · excess_i / Σ_k excess_k:
    //    demand_p = capacity_p / Σ excess over its neighbours (0 when none has any).
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t p = static_cast<std::size_t>(y) * w + x;
        double sum = 0;
        forNeighbours(x, y, [&](std::size_t k) { sum += excess(k); });
        demand[p] = sum > 0 ? capacity[p] / sum : 0.0;
      }
    // 2. A donor gives at most its excess: its requests are scaled down together.
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        double asked = 0;
        forNeighbours(x, y, [&](std::size_t p) { asked += demand[p]; });
        const double e = excess(i), requested = e * asked;
        // transfer i→p = demand_p · supply_i. When scaled down, a hair under the exact share
        // so that rounding in the sums cannot take the donor below the residual.
        supply[i] = requested > e ? e / asked * (1.0 - 1e-12) : e;
      }
    // 3. Apply: every transfer leaves one pixel and arrives at another.
    std::vector<double> next = I;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        double out = 0, in_ = 0;
        forNeighbours(x, y, [&](std::size_t k) {
          out += demand[k] * supply[i];
          in_ += demand[i] * supply[k];
        });
        // Mathematically never below the residual; rounding of nearly equal sums can leave
        // a denormal below zero, which is removed (a change of < 1e-300 in the total).
        next[i] = std::max(next[i] + in_ - out, 0.0);
      }
    cur.ink = std::move(next);
  }
  return cur;
}

InkField diffuseInk(const InkField& in, const std::vector<float>& absorbency, const DiffusionOptions& o) {
  validate(o);
  const InkField main = mainDiffusionDistance(in, o);
  return boundaryDiffusion(main, absorbency, strokeMask(in, o.threshold), o);
}

}  // namespace shanshui::ink
