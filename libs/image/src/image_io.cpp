#include "shanshui/image/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <system_error>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"

namespace shanshui::image {
namespace fs = std::filesystem;

namespace {

PixelDepth depthOf(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8: return PixelDepth::UInt8;
    case OIIO::TypeDesc::INT8: return PixelDepth::UInt8;
    case OIIO::TypeDesc::UINT16: return PixelDepth::UInt16;
    case OIIO::TypeDesc::INT16: return PixelDepth::Int16;
    case OIIO::TypeDesc::UINT32: return PixelDepth::UInt32;
    case OIIO::TypeDesc::INT32: return PixelDepth::Int32;
    case OIIO::TypeDesc::HALF: return PixelDepth::Half;
    case OIIO::TypeDesc::DOUBLE: return PixelDepth::Double;
    default: return PixelDepth::Float;
  }
}

OIIO::TypeDesc typeOf(PixelDepth d) {
  switch (d) {
    case PixelDepth::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelDepth::UInt16: return OIIO::TypeDesc::UINT16;
    case PixelDepth::Int16: return OIIO::TypeDesc::INT16;
    case PixelDepth::UInt32: return OIIO::TypeDesc::UINT32;
    case PixelDepth::Int32: return OIIO::TypeDesc::INT32;
    case PixelDepth::Half: return OIIO::TypeDesc::HALF;
    case PixelDepth::Float: return OIIO::TypeDesc::FLOAT;
    case PixelDepth::Double: return OIIO::TypeDesc::DOUBLE;
  }
  return OIIO::TypeDesc::FLOAT;
}

std::string oneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

double normalisationScale(PixelDepth depth) {
  switch (depth) {
    case PixelDepth::UInt8: return 255.0;
    case PixelDepth::UInt16: return 65535.0;
    case PixelDepth::Int16: return 32767.0;
    case PixelDepth::UInt32: return 4294967295.0;
    case PixelDepth::Int32: return 2147483647.0;
    default: return 1.0;
  }
}

PixelDepth parseDepth(const std::string& text) {
  if (text == "8") return PixelDepth::UInt8;
  if (text == "16") return PixelDepth::UInt16;
  if (text == "float" || text == "32") return PixelDepth::Float;
  throw makeError("--depth: '", text, "' is not a depth; expected 8, 16 or float");
}

const char* depthName(PixelDepth depth) {
  switch (depth) {
    case PixelDepth::UInt8: return "8";
    case PixelDepth::UInt16: return "16";
    case PixelDepth::Int16: return "int16";
    case PixelDepth::UInt32: return "uint32";
    case PixelDepth::Int32: return "int32";
    case PixelDepth::Half: return "half";
    case PixelDepth::Float: return "float";
    case PixelDepth::Double: return "double";
  }
  return "?";
}

Image loadImage(const fs::path& path, ImageInfo* info) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) throw makeError(name, ": no such file");
  if (fs::is_directory(path, ec)) throw makeError(name, ": is a directory, expected an image");
  if (fs::file_size(path, ec) == 0) throw makeError(name, ": empty file");

  // Keep straight alpha as stored (PNG, TIFF, GIF) instead of premultiplying on read.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(name, &config);
  if (!in) throw makeError(name, ": cannot read image: ", oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw makeError(name, ": zero-size image (", spec.width, "x", spec.height, "x",
                    spec.nchannels, ")");
  }
  if (spec.deep) throw makeError(name, ": deep images are not supported");
  if (spec.nchannels > 4) {
    throw makeError(name, ": ", spec.nchannels, " channels; expected 1 to 4");
  }
  const int channels = spec.nchannels;
  Image img(spec.width, spec.height, channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img.pixels.data())) {
    throw makeError(name, ": cannot read pixels (truncated or corrupt?): ", oneLine(in->geterror()));
  }
  const bool associated =
      img.hasAlpha() && spec.alpha_channel == channels - 1 &&
      spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0;
  const bool alphaOnly = channels == 1 && spec.alpha_channel == 0;
  in->close();
  for (float& v : img.pixels) {
    if (!std::isfinite(v)) throw makeError(name, ": contains NaN or infinite pixel values");
  }
  if (associated) {  // EXR and friends store premultiplied colour: undo it.
    const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
    for (std::size_t p = 0; p < n; ++p) {
      float* px = &img.pixels[p * channels];
      const float a = px[channels - 1];
      if (a > 0.0f) {
        for (int c = 0; c < channels - 1; ++c) px[c] /= a;
      }
    }
  }
  if (info) {
    info->depth = depthOf(spec.format);
    info->channels = channels;
    info->format = in->format_name();
    info->alpha_only = alphaOnly;
  }
  return img;
}

void saveImage(const Image& img, const fs::path& path, PixelDepth depth) {
  const std::string name = path.string();
  if (img.empty() || img.width <= 0 || img.height <= 0) {
    throw makeError(name, ": refusing to write an empty image (", img.width, "x", img.height, ")");
  }
  for (float v : img.pixels) {
    if (!std::isfinite(v)) throw makeError(name, ": refusing to write an image with NaN or infinite values");
  }
  {
    auto probe = OIIO::ImageOutput::create(name);
    if (!probe) {
      throw makeError(name, ": unknown image format for extension '", path.extension().string(),
                      "' (expected .png, .jpg, .tif, .exr, ...)");
    }
    (void)OIIO::geterror();
  }
  writeAtomically(path, [&](const fs::path& tmp) {
    auto out = OIIO::ImageOutput::create(tmp.string());
    if (!out) throw makeError(name, ": cannot create writer: ", oneLine(OIIO::geterror()));
    OIIO::TypeDesc type = typeOf(depth);
    OIIO::ImageSpec spec(img.width, img.height, img.channels, type);
    if (img.channels == 2) spec.channelnames = {"Y", "A"};  // so readers see grey + alpha
    if (img.hasAlpha()) {
      spec.alpha_channel = img.channels - 1;
      spec.attribute("oiio:UnassociatedAlpha", 1);
    }
    if (img.hasAlpha() && !out->supports("alpha")) {
      throw makeError(name, ": format '", out->format_name(),
                      "' cannot store alpha; composite over white first or use PNG/TIFF/EXR");
    }
    if (!out->open(tmp.string(), spec)) {
      throw makeError(name, ": cannot open for writing: ", oneLine(out->geterror()));
    }
    bool ok = false;
    if (img.hasAlpha() && std::string(out->format_name()) == "openexr") {
      // OpenEXR stores premultiplied colour by definition (its writer ignores the
      // unassociated hint); loadImage divides it back out.
      std::vector<float> premultiplied(img.pixels);
      for (std::size_t p = 0; p < premultiplied.size(); p += img.channels) {
        for (int c = 0; c + 1 < img.channels; ++c) premultiplied[p + c] *= premultiplied[p + img.channels - 1];
      }
      ok = out->write_image(OIIO::TypeDesc::FLOAT, premultiplied.data());
    } else if (type.is_floating_point()) {
      ok = out->write_image(OIIO::TypeDesc::FLOAT, img.pixels.data());
    } else {
      std::vector<float> clamped(img.pixels.size());
      std::transform(img.pixels.begin(), img.pixels.end(), clamped.begin(),
                     [](float v) { return std::clamp(v, 0.0f, 1.0f); });
      ok = out->write_image(OIIO::TypeDesc::FLOAT, clamped.data());
    }
    if (!ok || !out->close()) throw makeError(name, ": write failed: ", oneLine(out->geterror()));
  });
}

}  // namespace shanshui::image
