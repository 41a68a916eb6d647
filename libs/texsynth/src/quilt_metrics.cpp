#include "shanshui/texsynth/quilt_metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "shanshui/core/error.h"
#include "shanshui/core/parallel_for.h"
#include "shanshui/core/random.h"
#include "shanshui/texsynth/overlap_search.h"

namespace shanshui::texsynth {
namespace {

double squaredDistance(const float* a, const float* b, int channels) {
  double sum = 0.0;
  for (int c = 0; c < channels; ++c) {
    const double d = static_cast<double>(a[c]) - b[c];
    sum += d * d;
  }
  return sum;
}

struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

QuiltMetrics measureQuilt(const image::Image& sample, const QuiltResult& result, int block,
                          const QuiltMetricsOptions& opts) {
  const image::Image& out = result.image;
  const int w = out.width, h = out.height, ch = out.channels, sw = sample.width;
  SHANSHUI_CHECK_EQ(result.source.size(), static_cast<std::size_t>(w) * h);
  SHANSHUI_CHECK_EQ(ch, sample.channels);
  if (opts.patches < 1 || opts.patches > 100000) {
    throw makeError("quilt metrics: patches ", opts.patches, "; expected [1, 100000]");
  }
  if (opts.patch_size < 2) throw makeError("quilt metrics: patch size ", opts.patch_size, "; expected at least 2");
  QuiltMetrics m;
  auto src = [&](int x, int y) { return result.source[static_cast<std::size_t>(y) * w + x]; };

  // Seams and verbatim regions in one pass over neighbour pairs. A pair (p, q = p + d) is
  // continuous when q shows the sample pixel next to p's; otherwise it is a seam with cost
  // ‖out(q) − sample(src(p) + d)‖² + ‖out(p) − sample(src(q) − d)‖² (terms outside the sample
  // are left out and the rest scaled up).
  DisjointSets regions(static_cast<std::size_t>(w) * h);
  auto seamCost = [&](int x0, int y0, int x1, int y1, int dx, int dy, bool* continuous) {
    const int s0 = src(x0, y0), s1 = src(x1, y1);
    const int sx0 = s0 % sw, sy0 = s0 / sw, sx1 = s1 % sw, sy1 = s1 / sw;
    *continuous = sx1 == sx0 + dx && sy1 == sy0 + dy;
    if (*continuous) return 0.0;
    double cost = 0.0;
    int terms = 0;
    auto term = [&](int sx, int sy, int ox, int oy) {
      if (sx < 0 || sy < 0 || sx >= sample.width || sy >= sample.height) return;
      cost += squaredDistance(&sample.pixels[sample.index(sx, sy)], &out.pixels[out.index(ox, oy)], ch);
      ++terms;
    };
    term(sx0 + dx, sy0 + dy, x1, y1);
    term(sx1 - dx, sy1 - dy, x0, y0);
    return terms > 0 ? cost * 2.0 / terms : 0.0;
  };
  double seamSum = 0.0;
  auto visitPair = [&](int x0, int y0, int x1, int y1) {
    bool continuous = false;
    const double cost = seamCost(x0, y0, x1, y1, x1 - x0, y1 - y0, &continuous);
    if (continuous) {
      regions.join(y0 * w + x0, y1 * w + x1);
    } else {
      seamSum += cost;
      ++m.seam_edges;
    }
  };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (x + 1 < w) visitPair(x, y, x + 1, y);
      if (y + 1 < h) visitPair(x, y, x, y + 1);
    }
  }
  m.seam_error_per_edge = m.seam_edges > 0 ? seamSum / static_cast<double>(m.seam_edges) : 0.0;
  m.seam_error_per_overlap_pixel =
      result.stats.overlap_pixels > 0 ? seamSum / static_cast<double>(result.stats.overlap_pixels) : 0.0;

  // The same across the wrap: last column next to the first, last row next to the first.
  double wrapSum = 0.0;
  long long wrapSeams = 0;
  auto visitWrap = [&](int x0, int y0, int x1, int y1, int dx, int dy) {
    bool continuous = false;
    const double cost = seamCost(x0, y0, x1, y1, dx, dy, &continuous);
    wrapSum += cost;
    wrapSeams += !continuous;
  };
  for (int y = 0; y < h; ++y) visitWrap(w - 1, y, 0, y, 1, 0);
  for (int x = 0; x < w; ++x) visitWrap(x, h - 1, x, 0, 0, 1);
  m.wrap_seam_edges = wrapSeams;
  m.wrap_seam_error = wrapSum / static_cast<double>(w + h);

  std::vector<int> regionSize(static_cast<std::size_t>(w) * h, 0);
  int regionCount = 0, largest = 0;
  for (int p = 0; p < w * h; ++p) {
    const int r = regions.find(p);
    regionCount += regionSize[r] == 0;
    largest = std::max(largest, ++regionSize[r]);
  }
  m.verbatim_copy_ratio = static_cast<double>(largest) / (static_cast<double>(w) * h);
  m.largest_copy_blocks = static_cast<double>(largest) / (static_cast<double>(block) * block);
  m.mean_region_pixels = static_cast<double>(w) * h / regionCount;

  std::vector<long long> uses(static_cast<std::size_t>(sample.width) * sample.height, 0);
  for (std::int32_t s : result.source) ++uses[s];
  const double mean = static_cast<double>(w) * h / static_cast<double>(uses.size());
  double variance = 0.0;
  long long used = 0, most = 0;
  for (long long u : uses) {
    used += u > 0;
    most = std::max(most, u);
    variance += (u - mean) * (u - mean);
  }
  m.sample_coverage = static_cast<double>(used) / static_cast<double>(uses.size());
  m.usage_cv = std::sqrt(variance / static_cast<double>(uses.size())) / mean;
  m.usage_max_ratio = static_cast<double>(most) / mean;

  // Coherence: each random patch against every window of the sample, by FFT.
  const int p = std::min({opts.patch_size, sample.width, sample.height, w, h});
  const OverlapSearch search(sample, p);
  const cv::Mat fullMask(p, p, CV_8U, cv::Scalar(1));
  std::vector<double> nearest(opts.patches);
  parallelFor(opts.patches, resolveThreads(opts.threads), [&](int i) {
    const std::uint64_t r = streamValue(opts.seed, static_cast<std::uint64_t>(i));
    const int px = static_cast<int>(r % static_cast<std::uint64_t>(w - p + 1));
    const int py = static_cast<int>((r >> 32) % static_cast<std::uint64_t>(h - p + 1));
    image::Image patch(p, p, ch);
    for (int v = 0; v < p; ++v) {
      for (int u = 0; u < p; ++u) {
        for (int c = 0; c < ch; ++c) patch.at(u, v, c) = out.at(px + u, py + v, c);
      }
    }
    double best = 0.0;
    cv::minMaxLoc(search.errors(patch, fullMask, SearchMode::Fft), &best);
    nearest[i] = best / (static_cast<double>(p) * p);
  });
  m.coherence_mean = std::accumulate(nearest.begin(), nearest.end(), 0.0) / opts.patches;
  m.coherence_max = *std::max_element(nearest.begin(), nearest.end());
  return m;
}

}  // namespace shanshui::texsynth
