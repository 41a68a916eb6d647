#include "shanshui/image/image.h"

#include "shanshui/core/error.h"

namespace shanshui::image {

Image::Image(int width_, int height_, int channels_, float fill) : width(width_), height(height_), channels(channels_) {
  if (width_ < 0 || height_ < 0 || channels_ < 1 || channels_ > 4) {
    throw makeError("image: invalid size ", width_, "x", height_, "x", channels_,
                    " (expected non-negative size and 1-4 channels)");
  }
  pixels.assign(static_cast<std::size_t>(width_) * height_ * channels_, fill);
}

}  // namespace shanshui::image
