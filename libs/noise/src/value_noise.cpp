#include "shanshui/noise/value_noise.h"

#include <algorithm>
#include <vector>

#include "shanshui/core/error.h"
#include "shanshui/core/random.h"

namespace shanshui::noise {

namespace {

// Channel `ch` of erosionNoise into channel `ch` of `img` (channels 0 .. `ch` exist).
void erosionChannel(image::Image& img, int ch, std::uint64_t seed) {
  const int size = img.width, octaves = 3;
  std::vector<float> sum(static_cast<std::size_t>(size) * size, 0.0f);
  for (int o = 0; o < octaves; ++o) {
    const int cells = (ch == 0 ? kErosionCells : 32) << o;  // the added noise is finer than the erosion
    const float weight = 1.0f / static_cast<float>(1 << o);
    std::vector<float> lattice(static_cast<std::size_t>(cells) * cells);
    for (std::size_t i = 0; i < lattice.size(); ++i) {
      lattice[i] = static_cast<float>(
                       streamValue(seed ^ (0x9E37u * (ch + 1)) ^ (static_cast<std::uint64_t>(o) << 40), i) >> 11) *
                   (1.0f / 9007199254740992.0f);
    }
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const float fx = static_cast<float>(x) * cells / size, fy = static_cast<float>(y) * cells / size;
        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
        float tx = fx - x0, ty = fy - y0;
        tx = tx * tx * (3 - 2 * tx);
        ty = ty * ty * (3 - 2 * ty);
        auto at = [&](int i, int j) { return lattice[static_cast<std::size_t>(j % cells) * cells + (i % cells)]; };
        const float v = (at(x0, y0) * (1 - tx) + at(x0 + 1, y0) * tx) * (1 - ty) +
                        (at(x0, y0 + 1) * (1 - tx) + at(x0 + 1, y0 + 1) * tx) * ty;
        sum[static_cast<std::size_t>(y) * size + x] += weight * v;
      }
    }
  }
  // Stretch to [0, 1] so the erosion strength means the same for any seed.
  const auto [lo, hi] = std::minmax_element(sum.begin(), sum.end());
  const float range = std::max(*hi - *lo, 1e-6f);
  for (std::size_t i = 0; i < sum.size(); ++i)
    img.pixels[i * static_cast<std::size_t>(img.channels) + static_cast<std::size_t>(ch)] = (sum[i] - *lo) / range;
}

}  // namespace

image::Image erosionNoise(int size, std::uint64_t seed) {
  SHANSHUI_CHECK(size >= 8);
  image::Image img(size, size, 2);
  for (int ch = 0; ch < 2; ++ch) erosionChannel(img, ch, seed);
  return img;
}

image::Image erosionNoiseCoarse(int size, std::uint64_t seed) {
  SHANSHUI_CHECK(size >= 8);
  image::Image img(size, size, 1);
  erosionChannel(img, 0, seed);
  return img;
}

}  // namespace shanshui::noise
