#include "shanshui/image/opencv_interop.h"

#include "shanshui/core/error.h"

namespace shanshui::image {

cv::Mat asMat(Image& img) {
  return cv::Mat(img.height, img.width, CV_32FC(img.channels), img.pixels.data());
}

const cv::Mat asMat(const Image& img) {
  return cv::Mat(img.height, img.width, CV_32FC(img.channels), const_cast<float*>(img.pixels.data()));
}

Image imageFromMat(const cv::Mat& mat) {
  if (mat.dims != 2 || mat.channels() < 1 || mat.channels() > 4) {
    throw makeError("imageFromMat: expected a 2D Mat with 1-4 channels, got ", mat.dims, " dims and ", mat.channels(),
                    " channels");
  }
  double scale = 1.0;
  switch (mat.depth()) {
    case CV_8U:
      scale = 1.0 / 255.0;
      break;
    case CV_16U:
      scale = 1.0 / 65535.0;
      break;
    case CV_8S:
      scale = 1.0 / 127.0;
      break;
    case CV_16S:
      scale = 1.0 / 32767.0;
      break;
    default:
      break;
  }
  Image out(mat.cols, mat.rows, mat.channels());
  cv::Mat view = asMat(out);
  mat.convertTo(view, CV_32F, scale);
  SHANSHUI_CHECK(view.data == reinterpret_cast<uchar*>(out.pixels.data()));
  return out;
}

}  // namespace shanshui::image
