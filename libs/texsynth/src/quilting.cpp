#include "shanshui/texsynth/quilting.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "shanshui/core/error.h"
#include "shanshui/core/parallel_for.h"
#include "shanshui/core/random.h"

namespace shanshui::texsynth {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Block origins along one axis. Plain output: steps of B − O from 0 until the blocks cover
// `size`. Tileable output: n = ceil(size / step) origins spread over the period, so every
// overlap (including the wrap from the last block to the first) is at least O.
std::vector<int> blockOrigins(int size, int block, int overlap, bool wrap) {
  const int step = block - overlap;
  std::vector<int> origins;
  if (wrap) {
    const int n = (size + step - 1) / step;
    for (int i = 0; i < n; ++i) origins.push_back(static_cast<int>(static_cast<long long>(i) * size / n));
  } else {
    const int n = 1 + std::max(0, (size - block + step - 1) / step);
    for (int i = 0; i < n; ++i) origins.push_back(i * step);
  }
  return origins;
}

// Whether [a, a + len) and [b, b + len) meet, on a circle of `period` when period > 0.
bool intervalsMeet(int a, int b, int len, int period) {
  if (period <= 0) return a < b + len && b < a + len;
  const int ab = ((b - a) % period + period) % period;
  const int ba = ((a - b) % period + period) % period;
  return ab < len || ba < len;
}

struct Layout {
  std::vector<int> xs, ys;
  int canvasWidth = 0, canvasHeight = 0;
  bool wrap = false;
  int count() const { return static_cast<int>(xs.size() * ys.size()); }
};

// Blocks in raster order are grouped into waves: a block's wave is one more than the latest
// wave of any earlier block whose footprint it meets. Blocks of one wave do not meet each
// other, and each sees exactly the pixels it would see in plain raster order.
std::vector<std::vector<int>> waves(const Layout& L, int block) {
  const int nx = static_cast<int>(L.xs.size()), ny = static_cast<int>(L.ys.size());
  const int px = L.wrap ? L.canvasWidth : 0, py = L.wrap ? L.canvasHeight : 0;
  std::vector<int> wave(static_cast<std::size_t>(nx) * ny, 0);
  int last = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      int w = 0;
      for (int jj = 0; jj <= j; ++jj) {
        if (!intervalsMeet(L.ys[j], L.ys[jj], block, py)) continue;
        const int end = jj < j ? nx : i;
        for (int ii = 0; ii < end; ++ii) {
          if (intervalsMeet(L.xs[i], L.xs[ii], block, px)) w = std::max(w, wave[jj * nx + ii] + 1);
        }
      }
      wave[j * nx + i] = w;
      last = std::max(last, w);
    }
  }
  std::vector<std::vector<int>> groups(last + 1);
  for (int k = 0; k < nx * ny; ++k) groups[wave[k]].push_back(k);
  return groups;
}

struct BlockRecord {
  int candidates = 0;  // windows the block was drawn from (all of them without a search)
  long long overlapPixels = 0;
  double chosenError = 0.0;
  double auditRatio = 0.0;      // chosen / floored exhaustive minimum
  bool auditViolation = false;  // chosen error above the exhaustive search's threshold
  double auditSeconds = 0.0;
};

class Quilter {
 public:
  Quilter(const image::Image& sample, const QuiltOptions& opts, const Layout& layout)
      : sample_(sample),
        opts_(opts),
        L_(layout),
        search_(sample, opts.block),
        canvas_(layout.canvasWidth, layout.canvasHeight, sample.channels),
        filled_(static_cast<std::size_t>(layout.canvasWidth) * layout.canvasHeight, 0),
        source_(filled_.size(), -1) {}

  BlockRecord place(int k) {
    const int b = opts_.block;
    const int nx = static_cast<int>(L_.xs.size());
    const int ox = L_.xs[k % nx], oy = L_.ys[k / nx];
    image::Image old(b, b, sample_.channels);
    cv::Mat filled(b, b, CV_8U);
    long long overlapPixels = 0;
    for (int v = 0; v < b; ++v) {
      for (int u = 0; u < b; ++u) {
        const std::size_t p = canvasPixel(ox + u, oy + v);
        filled.at<std::uint8_t>(v, u) = filled_[p];
        overlapPixels += filled_[p];
        for (int c = 0; c < sample_.channels; ++c) old.at(u, v, c) = canvas_.pixels[p * sample_.channels + c];
      }
    }

    BlockRecord rec;
    rec.overlapPixels = overlapPixels;
    const std::uint64_t random = streamValue(opts_.seed, static_cast<std::uint64_t>(k));
    const int positionsX = search_.positionsX(), positionsY = search_.positionsY();
    const double floor = opts_.error_floor * static_cast<double>(overlapPixels * sample_.channels);
    int chosen = 0;  // index y·positionsX + x
    if (overlapPixels == 0 || opts_.search == SearchMode::Random) {
      rec.candidates = positionsX * positionsY;
      chosen = static_cast<int>(random % static_cast<std::uint64_t>(rec.candidates));
    } else {
      thread_local cv::Mat errors;
      search_.errors(old, filled, opts_.search, errors);
      double minError = 0.0;
      cv::minMaxLoc(errors, &minError);
      const double threshold = candidateThreshold(minError, overlapPixels * sample_.channels, opts_);
      std::vector<int> candidates;
      for (int y = 0; y < positionsY; ++y) {
        const double* row = errors.ptr<double>(y);
        for (int x = 0; x < positionsX; ++x) {
          if (row[x] <= threshold) candidates.push_back(y * positionsX + x);
        }
      }
      SHANSHUI_CHECK(!candidates.empty());
      rec.candidates = static_cast<int>(candidates.size());
      chosen = candidates[random % candidates.size()];
    }
    const int sx = chosen % positionsX, sy = chosen / positionsX;
    if (overlapPixels > 0) {
      rec.chosenError = search_.errorAt(old, filled, sx, sy);
      if (opts_.audit) {
        const auto start = Clock::now();
        double exactMin = 0.0;
        cv::minMaxLoc(search_.errors(old, filled, SearchMode::Exhaustive), &exactMin);
        rec.auditRatio = rec.chosenError / std::max(exactMin, floor);
        rec.auditViolation = rec.chosenError > candidateThreshold(exactMin, overlapPixels * sample_.channels, opts_);
        rec.auditSeconds = secondsSince(start);
      }
    }

    image::Image patch(b, b, sample_.channels);
    for (int v = 0; v < b; ++v) {
      for (int u = 0; u < b; ++u) {
        for (int c = 0; c < sample_.channels; ++c) patch.at(u, v, c) = sample_.at(sx + u, sy + v, c);
      }
    }
    const cv::Mat isNew = seamMask(old, patch, filled, opts_.seam);
    for (int v = 0; v < b; ++v) {
      for (int u = 0; u < b; ++u) {
        if (!isNew.at<std::uint8_t>(v, u)) continue;
        const std::size_t p = canvasPixel(ox + u, oy + v);
        for (int c = 0; c < sample_.channels; ++c) canvas_.pixels[p * sample_.channels + c] = patch.at(u, v, c);
        filled_[p] = 1;
        source_[p] = (sy + v) * sample_.width + (sx + u);
      }
    }
    return rec;
  }

  QuiltResult finish(int width, int height) {
    QuiltResult r;
    r.image = image::Image(width, height, sample_.channels);
    r.source.resize(static_cast<std::size_t>(width) * height);
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        const std::size_t p = canvasPixel(x, y);
        SHANSHUI_CHECK(filled_[p]);
        r.source[static_cast<std::size_t>(y) * width + x] = source_[p];
        for (int c = 0; c < sample_.channels; ++c) r.image.at(x, y, c) = canvas_.pixels[p * sample_.channels + c];
      }
    }
    return r;
  }

 private:
  std::size_t canvasPixel(int x, int y) const {
    if (L_.wrap) {
      x %= L_.canvasWidth;
      y %= L_.canvasHeight;
    }
    return static_cast<std::size_t>(y) * L_.canvasWidth + x;
  }

  const image::Image& sample_;
  const QuiltOptions& opts_;
  const Layout& L_;
  OverlapSearch search_;
  image::Image canvas_;
  std::vector<std::uint8_t> filled_;
  std::vector<std::int32_t> source_;
};

}  // namespace

double candidateThreshold(double minError, long long values, const QuiltOptions& opts) {
  const double threshold = (1.0 + opts.tolerance) * std::max(minError, opts.error_floor * static_cast<double>(values));
  return threshold + 1e-9 * (threshold + static_cast<double>(values));
}

int QuiltOptions::resolvedOverlap() const {
  return overlap >= 0 ? overlap : std::max(1, static_cast<int>(std::lround(block / 6.0)));
}

void validate(const QuiltOptions& opts, int sampleWidth, int sampleHeight, const std::string& what) {
  if (opts.block < 3) throw makeError("quilt: block ", opts.block, "; expected at least 3 pixels");
  if (opts.block > sampleWidth || opts.block > sampleHeight) {
    throw makeError(what, ": sample is ", sampleWidth, "x", sampleHeight, ", smaller than block ", opts.block,
                    "; use a smaller --block (at most ", std::min(sampleWidth, sampleHeight), ")");
  }
  const int overlap = opts.resolvedOverlap();
  if (overlap < 1 || overlap >= opts.block) {
    throw makeError("quilt: overlap ", overlap, "; expected 1 <= overlap < block (", opts.block, ")");
  }
  if (opts.width < opts.block || opts.height < opts.block) {
    throw makeError("quilt: output size ", opts.width, "x", opts.height, " is smaller than block ", opts.block);
  }
  if (static_cast<long long>(opts.width) * opts.height > (1ll << 28)) {
    throw makeError("quilt: output size ", opts.width, "x", opts.height, " is larger than 2^28 pixels");
  }
  if (!(opts.tolerance >= 0.0 && opts.tolerance <= 1e9)) {
    throw makeError("quilt: tolerance ", opts.tolerance, "; expected a value in [0, 1e9]");
  }
  if (!(opts.error_floor >= 0.0 && opts.error_floor <= 1.0)) {
    throw makeError("quilt: error floor ", opts.error_floor, "; expected a value in [0, 1]");
  }
  if (opts.threads < 0) throw makeError("quilt: threads ", opts.threads, "; expected 0 (all) or more");
}

QuiltResult quilt(const image::Image& sample, const QuiltOptions& opts, const std::string& what) {
  if (sample.empty()) throw makeError(what, ": empty sample");
  validate(opts, sample.width, sample.height, what);
  for (float v : sample.pixels) {
    if (!std::isfinite(v)) throw makeError(what, ": sample contains NaN or infinite values");
  }
  const auto start = Clock::now();
  const int overlap = opts.resolvedOverlap();
  Layout layout;
  layout.wrap = opts.tileable;
  layout.xs = blockOrigins(opts.width, opts.block, overlap, opts.tileable);
  layout.ys = blockOrigins(opts.height, opts.block, overlap, opts.tileable);
  layout.canvasWidth = opts.tileable ? opts.width : layout.xs.back() + opts.block;
  layout.canvasHeight = opts.tileable ? opts.height : layout.ys.back() + opts.block;

  const std::vector<std::vector<int>> groups = waves(layout, opts.block);
  const int threads = resolveThreads(opts.threads);
  Quilter quilter(sample, opts, layout);
  std::vector<BlockRecord> records(layout.count());
  int done = 0;
  for (const std::vector<int>& group : groups) {
    parallelFor(static_cast<int>(group.size()), threads, [&](int i) { records[group[i]] = quilter.place(group[i]); });
    done += static_cast<int>(group.size());
    if (opts.progress) opts.progress(done, layout.count());
  }
  QuiltResult result = quilter.finish(opts.width, opts.height);

  QuiltStats& s = result.stats;
  s.blocks = layout.count();
  s.blocks_x = static_cast<int>(layout.xs.size());
  s.blocks_y = static_cast<int>(layout.ys.size());
  s.waves = static_cast<int>(groups.size());
  s.threads = threads;
  double errorSum = 0.0, ratioSum = 0.0;
  long long candidateSum = 0, violations = 0;
  int searched = 0;
  for (const BlockRecord& r : records) {  // summed in block order: the same for any thread count
    s.overlap_pixels += r.overlapPixels;
    errorSum += r.chosenError;
    s.audit_seconds += r.auditSeconds;
    if (r.overlapPixels > 0) {
      ++searched;
      candidateSum += r.candidates;
      ratioSum += r.auditRatio;
      violations += r.auditViolation;
    }
  }
  s.overlap_error_per_pixel = s.overlap_pixels > 0 ? errorSum / static_cast<double>(s.overlap_pixels) : 0.0;
  s.mean_candidates = searched > 0 ? static_cast<double>(candidateSum) / searched : 0.0;
  if (opts.audit) {
    s.search_error_ratio = searched > 0 ? ratioSum / searched : 1.0;
    s.search_rule_violations = searched > 0 ? static_cast<double>(violations) / searched : 0.0;
  }
  s.seconds = secondsSince(start);
  return result;
}

}  // namespace shanshui::texsynth
