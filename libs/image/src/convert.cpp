#include "shanshui/image/convert.h"

namespace shanshui::image {

Image compositeOverWhite(const Image& img) {
  if (!img.hasAlpha()) return img;
  const int colour = img.channels - 1;
  Image out(img.width, img.height, colour);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t p = 0; p < n; ++p) {
    const float* src = &img.pixels[p * img.channels];
    const float a = src[colour];
    for (int c = 0; c < colour; ++c) out.pixels[p * colour + c] = a * src[c] + (1.0f - a);
  }
  return out;
}

Image toGrey(const Image& img) {
  const Image opaque = compositeOverWhite(img);
  if (opaque.channels == 1) return opaque;
  Image out(opaque.width, opaque.height, 1);
  const std::size_t n = static_cast<std::size_t>(opaque.width) * opaque.height;
  for (std::size_t p = 0; p < n; ++p) {
    const float* s = &opaque.pixels[p * 3];
    out.pixels[p] = kLumaR * s[0] + kLumaG * s[1] + kLumaB * s[2];
  }
  return out;
}

Image toRgb(const Image& img) {
  const Image opaque = compositeOverWhite(img);
  if (opaque.channels == 3) return opaque;
  Image out(opaque.width, opaque.height, 3);
  for (std::size_t p = 0; p < opaque.pixels.size(); ++p) {
    for (int c = 0; c < 3; ++c) out.pixels[p * 3 + c] = opaque.pixels[p];
  }
  return out;
}

Image toRgba(const Image& img) {
  if (img.channels == 4) return img;
  Image out(img.width, img.height, 4, 1.0f);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t p = 0; p < n; ++p) {
    const float* s = &img.pixels[p * img.channels];
    float* d = &out.pixels[p * 4];
    switch (img.channels) {
      case 1:
        d[0] = d[1] = d[2] = s[0];
        break;
      case 2:
        d[0] = d[1] = d[2] = s[0];
        d[3] = s[1];
        break;
      default:
        d[0] = s[0];
        d[1] = s[1];
        d[2] = s[2];
        break;
    }
  }
  return out;
}

}  // namespace shanshui::image
