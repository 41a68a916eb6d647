// Channel conversions between the layouts of Image.
#pragma once

#include "shanshui/image/image.h"

namespace shanshui::image {

//! Luma weights for RGB to grey (ITU-R BT.601): 0.299 R + 0.587 G + 0.114 B.
inline constexpr float kLumaR = 0.299f;
inline constexpr float kLumaG = 0.587f;
inline constexpr float kLumaB = 0.114f;

//! Drops alpha by compositing over white: c' = a·c + (1 − a). 1 and 3 channels pass through.
Image compositeOverWhite(const Image& img);

//! One grey channel: alpha composited over white first, then the luma weights above.
Image toGrey(const Image& img);

//! Three channels (grey replicated; alpha composited over white).
Image toRgb(const Image& img);

//! Four channels (alpha 1 where the input had none).
Image toRgba(const Image& img);

}  // namespace shanshui::image
