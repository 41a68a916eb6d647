#include "shanshui/render/canvas_metrics.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <opencv2/core.hpp>

#include "shanshui/core/error.h"
#include "shanshui/render/ink_renderer.h"

namespace shanshui::render {

namespace {

glm::dmat4 viewProjection(const OrbitCamera& c, double aspect) {
  return glm::dmat4(c.projection(aspect)) * glm::dmat4(c.view());
}

}  // namespace

image::Image viewPositions(const InkRenderer& renderer, const OrbitCamera& camera) {
  image::Image out = renderer.worldPositions();
  const CanvasPass* canvas = renderer.canvas();
  if (!canvas || canvas->passName() != std::string("canvas")) return out;
  const double aspect = static_cast<double>(out.width) / out.height;
  const glm::dmat4 inverse = glm::inverse(viewProjection(camera, aspect));
  const glm::dvec3 eye = camera.eye(), centre = canvas->domeCentre();
  const double radius = canvas->domeRadius();
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      if (out.at(x, y, 3) > 0) continue;
      const glm::dvec4 far = inverse * glm::dvec4((x + 0.5) / out.width * 2 - 1, 1 - (y + 0.5) / out.height * 2, 1, 1);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(far) / far.w - eye);
      // |eye + t dir − centre| = radius, the far root (the eye is inside the dome).
      const glm::dvec3 oc = eye - centre;
      const double b = glm::dot(oc, dir), c = glm::dot(oc, oc) - radius * radius;
      const double disc = b * b - c;
      if (disc < 0) continue;
      const glm::dvec3 p = eye + (-b + std::sqrt(disc)) * dir;
      for (int k = 0; k < 3; ++k) out.at(x, y, k) = static_cast<float>(p[k]);
      out.at(x, y, 3) = 1.0f;
    }
  return out;
}

WarpError warpingError(const WarpView& previous, const WarpView& current) {
  const int w = current.values.width, h = current.values.height;
  SHANSHUI_CHECK(previous.values.width == w && previous.values.height == h);
  const double aspect = static_cast<double>(w) / h;
  const glm::dmat4 prev_vp = viewProjection(previous.camera, aspect);
  const glm::dvec3 prev_eye = previous.camera.eye();
  const glm::dvec3 forward = glm::normalize(previous.camera.target - prev_eye);
  double sum = 0, sum2 = 0, err = 0;
  std::size_t n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (current.positions.at(x, y, 3) <= 0) continue;
      const glm::dvec3 p(current.positions.at(x, y, 0), current.positions.at(x, y, 1), current.positions.at(x, y, 2));
      const glm::dvec4 clip = prev_vp * glm::dvec4(p, 1.0);
      if (clip.w <= 0) continue;
      // Pixel coordinates in the previous image, row 0 at the top, centres at +0.5.
      const double u = (clip.x / clip.w * 0.5 + 0.5) * w - 0.5, v = (0.5 - clip.y / clip.w * 0.5) * h - 0.5;
      if (u < 0 || v < 0 || u > w - 1 || v > h - 1) continue;
      const int ui = std::min(static_cast<int>(u), w - 2), vi = std::min(static_cast<int>(v), h - 2);
      const double fu = u - ui, fv = v - vi;
      // Occlusion: the previous view must have seen (about) this point there.
      const int nu = static_cast<int>(std::lround(u)), nv = static_cast<int>(std::lround(v));
      if (previous.positions.at(nu, nv, 3) <= 0) continue;
      const glm::dvec3 q(previous.positions.at(nu, nv, 0), previous.positions.at(nu, nv, 1),
                         previous.positions.at(nu, nv, 2));
      const double dp = glm::dot(p - prev_eye, forward), dq = glm::dot(q - prev_eye, forward);
      if (std::abs(dp - dq) > 0.02 * dp) continue;
      auto at = [&](int i, int j) { return static_cast<double>(previous.values.at(i, j, 0)); };
      const double warped = (at(ui, vi) * (1 - fu) + at(ui + 1, vi) * fu) * (1 - fv) +
                            (at(ui, vi + 1) * (1 - fu) + at(ui + 1, vi + 1) * fu) * fv;
      const double c = current.values.at(x, y, 0);
      err += (c - warped) * (c - warped);
      sum += c;
      sum2 += c * c;
      ++n;
    }
  WarpError out;
  if (n == 0) return out;
  const double mean = sum / static_cast<double>(n);
  out.mse = err / static_cast<double>(n);
  out.variance = sum2 / static_cast<double>(n) - mean * mean;
  out.coverage = static_cast<double>(n) / (static_cast<double>(w) * h);
  return out;
}

namespace {

// The periodogram of a one-channel image as radialPowerSpectrum describes it, calling
// visit(fx, fy, power) for every bin but the mean (fx, fy in cycles per pixel, in
// (−1/2, 1/2]).
template <typename Visit>
void visitPeriodogram(const image::Image& img, Visit visit) {
  const int w = img.width, h = img.height;
  double sum = 0;
  for (float v : img.pixels) sum += v;
  const double mean = sum / (static_cast<double>(w) * h);
  cv::Mat m(h, w, CV_64F);
  double window_energy = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double hx = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * (x + 0.5) / w);
      const double hy = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * (y + 0.5) / h);
      m.at<double>(y, x) = (img.at(x, y, 0) - mean) * hx * hy;
      window_energy += hx * hx * hy * hy;
    }
  cv::Mat f;
  cv::dft(m, f, cv::DFT_COMPLEX_OUTPUT);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (x == 0 && y == 0) continue;
      const double fx = (x <= w / 2 ? x : x - w) / static_cast<double>(w),
                   fy = (y <= h / 2 ? y : y - h) / static_cast<double>(h);
      const cv::Vec2d c = f.at<cv::Vec2d>(y, x);
      visit(fx, fy, (c[0] * c[0] + c[1] * c[1]) / window_energy);
    }
}

}  // namespace

std::vector<double> radialPowerSpectrum(const image::Image& img) {
  const int rings = std::min(img.width, img.height);
  const auto bins = static_cast<std::size_t>(rings / 2);
  std::vector<double> power(bins, 0.0), count(bins, 0.0);
  visitPeriodogram(img, [&](double fx, double fy, double p) {
    const auto b = static_cast<std::size_t>(std::hypot(fx, fy) * rings);
    if (b == 0 || b >= bins) return;  // the lowest ring and beyond Nyquist
    power[b] += p;
    count[b] += 1;
  });
  for (std::size_t b = 1; b < bins; ++b) power[b] = count[b] > 0 ? power[b] / count[b] : 0.0;
  return power;
}

double powerShareAbove(const image::Image& img, double frequency) {
  double above = 0, total = 0;
  visitPeriodogram(img, [&](double fx, double fy, double p) {
    total += p;
    if (std::hypot(fx, fy) > frequency) above += p;
  });
  return total > 0 ? above / total : 0.0;
}

std::vector<double> orientationShares(const image::Image& img, int sectors, double low, double high) {
  std::vector<double> share(static_cast<std::size_t>(std::max(sectors, 1)), 0.0);
  double total = 0;
  visitPeriodogram(img, [&](double fx, double fy, double p) {
    const double r = std::hypot(fx, fy);
    if (r < low || r > high) return;
    // The direction of the frequency vector, folded to [0°, 180°) and shifted half a sector
    // so that sector 0 is centred on 0°.
    double deg = std::atan2(fy, fx) * 180 / std::numbers::pi + 90.0 / static_cast<double>(share.size());
    deg = std::fmod(std::fmod(deg, 180.0) + 180.0, 180.0);
    share[std::min(share.size() - 1, static_cast<std::size_t>(deg / (180.0 / static_cast<double>(share.size()))))] += p;
    total += p;
  });
  for (double& s : share) s = total > 0 ? s / total : 0.0;
  return share;
}

namespace {

// Ring index (+ 1/2) of the centroid of a radial profile where it is above half its
// maximum (element 0, the mean, left out); 0 for a profile without power.
double halfMaximumCentroid(const std::vector<double>& profile) {
  double top = 0;
  for (std::size_t b = 1; b < profile.size(); ++b) top = std::max(top, profile[b]);
  double weighted = 0, total = 0;
  for (std::size_t b = 1; b < profile.size(); ++b) {
    if (profile[b] < 0.5 * top) continue;
    weighted += (static_cast<double>(b) + 0.5) * profile[b];
    total += profile[b];
  }
  return total > 0 ? weighted / total : 0.0;
}

}  // namespace

SpectrumPeak spectrumPeak(const image::Image& img) {
  return spectrumPeak(std::vector<image::Image>{img});
}

SpectrumPeak spectrumPeak(const std::vector<image::Image>& realisations) {
  SHANSHUI_CHECK(!realisations.empty());
  const int w = realisations.front().width, h = realisations.front().height;
  std::vector<double> mean_power;
  double contrast = 0;
  for (const image::Image& img : realisations) {
    SHANSHUI_CHECK(img.width == w && img.height == h && img.channels == 1);
    double sum = 0, sum2 = 0;
    for (float v : img.pixels) {
      sum += v;
      sum2 += static_cast<double>(v) * v;
    }
    const double mean = sum / (static_cast<double>(w) * h);
    contrast += std::sqrt(std::max(sum2 / (static_cast<double>(w) * h) - mean * mean, 0.0)) /
                static_cast<double>(realisations.size());
    const std::vector<double> power = radialPowerSpectrum(img);
    mean_power.resize(power.size(), 0.0);
    for (std::size_t b = 0; b < power.size(); ++b) mean_power[b] += power[b] / static_cast<double>(realisations.size());
  }
  // The peaks as centroids of the radial profiles where they are above half their maximum:
  // a single periodogram is noisy bin to bin, the centroid of the peak's top is not. The
  // energy of a ring is its mean power times its circumference, 2π(b + 1/2).
  std::vector<double> energy(mean_power.size(), 0.0);
  for (std::size_t b = 1; b < mean_power.size(); ++b) energy[b] = mean_power[b] * (static_cast<double>(b) + 0.5);
  const double peak = halfMaximumCentroid(mean_power), energy_peak = halfMaximumCentroid(energy);
  double all_weighted = 0, all_total = 0;
  for (std::size_t b = 1; b < mean_power.size(); ++b) {
    all_weighted += (static_cast<double>(b) + 0.5) * mean_power[b];
    all_total += mean_power[b];
  }
  const double mean_frequency = all_total > 0 ? all_weighted / all_total : 0.0;
  const double rings = std::min(w, h);
  return {peak / rings, mean_frequency / rings, contrast, energy_peak / rings};
}

}  // namespace shanshui::render
