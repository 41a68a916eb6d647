// The float image type shared by every shanshui library.
#pragma once

#include <cstddef>
#include <vector>

namespace shanshui::image {

//! Interleaved float pixels, row-major, row 0 at the top. Channels: 1 grey, 2 grey+alpha,
//! 3 RGB, 4 RGBA. Colour values are nominally in [0,1]; alpha is straight (not
//! premultiplied). Height fields and other data images may hold any finite value.
struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int width_, int height_, int channels_, float fill = 0.0f);

  bool empty() const { return pixels.empty(); }
  std::size_t index(int x, int y, int c = 0) const { return (static_cast<std::size_t>(y) * width + x) * channels + c; }
  float& at(int x, int y, int c = 0) { return pixels[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return pixels[index(x, y, c)]; }
  bool hasAlpha() const { return channels == 2 || channels == 4; }
};

}  // namespace shanshui::image
