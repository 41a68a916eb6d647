// Views of Image as cv::Mat and back. Channel order is whatever the Image holds (RGB);
// OpenCV's own BGR convention only matters to its file I/O, which shanshui does not use.
#pragma once

#include <opencv2/core.hpp>

#include "shanshui/image/image.h"

namespace shanshui::image {

//! A CV_32FC(channels) header over img.pixels: no copy; valid while img is alive and
//! not resized. Writes through the Mat change the Image.
cv::Mat asMat(Image& img);

//! Read-only view (a copy-free header; the caller must not write through it).
const cv::Mat asMat(const Image& img);

//! Copies any 2D Mat of 1-4 channels into an Image; integer depths are normalised to
//! [0,1] (8U by 255, 16U by 65535), float depths are taken as they are.
Image imageFromMat(const cv::Mat& mat);

}  // namespace shanshui::image
