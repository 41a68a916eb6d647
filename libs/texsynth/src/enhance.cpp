#include "shanshui/texsynth/enhance.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "shanshui/core/error.h"
#include "shanshui/core/parallel_for.h"
#include "shanshui/image/convert.h"

namespace shanshui::texsynth {
namespace {

constexpr int kBins = 65536;  // one bin per 16-bit level; 8-bit levels land on bins exactly

int colourChannels(const image::Image& img) {
  return img.hasAlpha() ? img.channels - 1 : img.channels;
}

// Counts values per 1/65535 bin; also rejects NaN and values outside [0, 1]. The pixels are
// split into one share per core, each counted into its own bins, then summed.
std::vector<std::uint64_t> histogram(const image::Image& img, const std::string& what) {
  const int colour = colourChannels(img);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  const int shares = static_cast<int>(std::min<std::size_t>(resolveThreads(0), std::max<std::size_t>(1, n >> 16)));
  struct Share {
    std::vector<std::uint64_t> bins = std::vector<std::uint64_t>(kBins, 0);
    std::size_t outside = 0;
    bool nan = false;
    float lo = 0.0f, hi = 1.0f;
  };
  std::vector<Share> counted(shares);
  parallelFor(shares, shares, [&](int i) {
    Share& share = counted[i];
    for (std::size_t p = n * i / shares; p < n * (i + 1) / shares; ++p) {
      const float* px = &img.pixels[p * img.channels];
      for (int c = 0; c < colour; ++c) {
        const float v = px[c];
        if (!(v >= 0.0f && v <= 1.0f)) {  // also catches NaN
          share.nan = share.nan || std::isnan(v);
          ++share.outside;
          share.lo = std::min(share.lo, v);
          share.hi = std::max(share.hi, v);
          continue;
        }
        ++share.bins[static_cast<std::size_t>(v * (kBins - 1) + 0.5f)];  // lround for v in [0, 1], without libm
      }
    }
  });
  Share& all = counted[0];
  for (int i = 1; i < shares; ++i) {
    for (int b = 0; b < kBins; ++b) all.bins[b] += counted[i].bins[b];
    all.outside += counted[i].outside;
    all.nan = all.nan || counted[i].nan;
    all.lo = std::min(all.lo, counted[i].lo);
    all.hi = std::max(all.hi, counted[i].hi);
  }
  if (all.nan) throw makeError(what, ": contains NaN values");
  if (all.outside > 0) {
    throw makeError(what, ": ", all.outside, " values outside [0, 1] (min ", all.lo, ", max ", all.hi,
                    "); contrast enhancement expects values in [0, 1]");
  }
  return std::move(all.bins);
}

double binPercentile(const std::vector<std::uint64_t>& bins, std::uint64_t total, double p) {
  // Smallest bin whose cumulative count reaches ceil(p% of total), at least one value.
  const auto need = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::ceil(p / 100.0 * total)));
  std::uint64_t sum = 0;
  for (int b = 0; b < kBins; ++b) {
    sum += bins[b];
    if (sum >= need) return static_cast<double>(b) / (kBins - 1);
  }
  return 1.0;
}

void checkUnit(double v, const char* name) {
  if (!(v >= 0.0 && v <= 1.0)) throw makeError("enhance: ", name, " = ", v, "; expected a value in [0, 1]");
}

}  // namespace

ValueRange percentileRange(const image::Image& img, double low_percent, double high_percent) {
  const std::vector<std::uint64_t> bins = histogram(img, "image");
  const std::uint64_t total = static_cast<std::uint64_t>(img.width) * img.height * colourChannels(img);
  return {binPercentile(bins, total, low_percent), binPercentile(bins, total, high_percent)};
}

image::Image enhanceContrast(image::Image input, const EnhanceOptions& opts, EnhanceReport* report,
                             const std::string& what) {
  if (input.empty()) throw makeError(what, ": empty image");
  checkUnit(opts.output_range.low, "output range c");
  checkUnit(opts.output_range.high, "output range d");
  if (opts.output_range.low == opts.output_range.high) {
    throw makeError("enhance: output range c:d = ", opts.output_range.low, ":", opts.output_range.high,
                    "; c and d must differ");
  }
  if (opts.input_range) {
    checkUnit(opts.input_range->low, "input range a");
    checkUnit(opts.input_range->high, "input range b");
    if (!(opts.input_range->high > opts.input_range->low)) {
      throw makeError("enhance: input range a:b = ", opts.input_range->low, ":", opts.input_range->high,
                      "; b must be greater than a");
    }
  } else if (!(opts.low_percentile >= 0.0 && opts.low_percentile < opts.high_percentile &&
               opts.high_percentile <= 100.0)) {
    throw makeError("enhance: percentiles ", opts.low_percentile, ":", opts.high_percentile,
                    "; expected 0 <= low < high <= 100");
  }

  image::Image img = opts.colour || input.channels == 1 ? std::move(input) : image::toGrey(input);
  const std::vector<std::uint64_t> bins = histogram(img, what);
  const std::uint64_t total = static_cast<std::uint64_t>(img.width) * img.height * colourChannels(img);

  ValueRange range;
  if (opts.input_range) {
    range = *opts.input_range;
  } else {
    range = {binPercentile(bins, total, opts.low_percentile), binPercentile(bins, total, opts.high_percentile)};
    if (!(range.high > range.low)) {
      throw makeError(what, ": no contrast: the ", opts.low_percentile, "% and ", opts.high_percentile,
                      "% percentiles are both ", range.low, "; give --range A:B or use another sample");
    }
  }

  // The same arithmetic as OpenImageIO's contrast_remap + clamp (the test oracle):
  // t = (f - a) / (b - a) as a product with the float reciprocal, g = c (1 - t) + d t.
  const float a = static_cast<float>(range.low);
  const float inv = 1.0f / (static_cast<float>(range.high) - a);
  const float c = static_cast<float>(opts.output_range.low);
  const float d = static_cast<float>(opts.output_range.high);
  const float lo = std::min(c, d), hi = std::max(c, d);
  const int colour = colourChannels(img);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  const int shares = resolveThreads(0);
  parallelFor(shares, shares, [&](int i) {
    for (std::size_t p = n * i / shares; p < n * (i + 1) / shares; ++p) {
      float* px = &img.pixels[p * img.channels];
      for (int ch = 0; ch < colour; ++ch) {
        const float t = (px[ch] - a) * inv;
        px[ch] = std::clamp(c * (1.0f - t) + d * t, lo, hi);
      }
    }
  });
  if (report) {
    // Counted on the histogram grid, like the percentiles: a value equal to b is not above b
    // even where float rounding puts it a hair over.
    const auto binOf = [](double v) { return static_cast<std::size_t>(std::lround(v * (kBins - 1))); };
    std::uint64_t below = 0, above = 0;
    for (std::size_t b = 0; b < bins.size(); ++b) {
      below += b <= binOf(range.low) ? bins[b] : 0;
      above += b > binOf(range.high) ? bins[b] : 0;
    }
    report->input_range = range;
    report->clipped_low = static_cast<double>(below) / static_cast<double>(total);
    report->clipped_high = static_cast<double>(above) / static_cast<double>(total);
  }
  return img;
}

}  // namespace shanshui::texsynth
