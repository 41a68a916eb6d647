// libshanshui_image_oiio.so: every format but PNG, JPEG and binary PNM, through OpenImageIO
// (TIFF, OpenEXR, GIF, BMP, Targa, HDR, ASCII PNM, CMYK JPEG, ...). Built as a module and
// loaded by image_io.cpp on first use, so tools that never meet these formats do not pay
// for OpenImageIO's ~260 shared libraries at start-up. Errors go back as messages.
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "codecs.h"

namespace shanshui::image::detail {
namespace {

PixelDepth depthOf(OIIO::TypeDesc t) {
  switch (t.basetype) {
    case OIIO::TypeDesc::UINT8:
      return PixelDepth::UInt8;
    case OIIO::TypeDesc::INT8:
      return PixelDepth::UInt8;
    case OIIO::TypeDesc::UINT16:
      return PixelDepth::UInt16;
    case OIIO::TypeDesc::INT16:
      return PixelDepth::Int16;
    case OIIO::TypeDesc::UINT32:
      return PixelDepth::UInt32;
    case OIIO::TypeDesc::INT32:
      return PixelDepth::Int32;
    case OIIO::TypeDesc::HALF:
      return PixelDepth::Half;
    case OIIO::TypeDesc::DOUBLE:
      return PixelDepth::Double;
    default:
      return PixelDepth::Float;
  }
}

OIIO::TypeDesc typeOf(PixelDepth d) {
  switch (d) {
    case PixelDepth::UInt8:
      return OIIO::TypeDesc::UINT8;
    case PixelDepth::UInt16:
      return OIIO::TypeDesc::UINT16;
    case PixelDepth::Int16:
      return OIIO::TypeDesc::INT16;
    case PixelDepth::UInt32:
      return OIIO::TypeDesc::UINT32;
    case PixelDepth::Int32:
      return OIIO::TypeDesc::INT32;
    case PixelDepth::Half:
      return OIIO::TypeDesc::HALF;
    case PixelDepth::Float:
      return OIIO::TypeDesc::FLOAT;
    case PixelDepth::Double:
      return OIIO::TypeDesc::DOUBLE;
  }
  return OIIO::TypeDesc::FLOAT;
}

std::string oneLine(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// Codec libraries behind OpenImageIO (libtiff, giflib) may print to stderr before
// OpenImageIO reports the same error; while a file is decoded or encoded, stderr goes to a
// scratch file so the tool's one line is the only one.
class QuietStderr {
 public:
  QuietStderr() {
    std::fflush(stderr);
    scratch_ = std::tmpfile();
    if (scratch_ == nullptr) return;
    saved_ = ::dup(2);
    if (saved_ < 0 || ::dup2(::fileno(scratch_), 2) < 0) restore();
  }
  ~QuietStderr() {
    restore();
    if (scratch_ != nullptr) std::fclose(scratch_);
  }
  QuietStderr(const QuietStderr&) = delete;
  QuietStderr& operator=(const QuietStderr&) = delete;

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    ::dup2(saved_, 2);
    ::close(saved_);
    saved_ = -1;
  }
  std::FILE* scratch_ = nullptr;
  int saved_ = -1;
};

void load(const std::string& name, const std::string& format, std::uintmax_t memory_budget, Decoded* out) {
  const QuietStderr quiet;
  // One reader: the one the first bytes named, else the extension's. OpenImageIO would
  // otherwise try every reader it has on a file its extension's reader refused, each
  // reading what it likes of a file that may be gigabytes of something else.
  static const bool one_reader = OIIO::attribute("try_all_readers", 0);
  (void)one_reader;
  // Keep straight alpha as stored (TIFF, GIF) instead of premultiplying on read.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  std::unique_ptr<OIIO::ImageInput> in;
  if (format.empty()) {
    in = OIIO::ImageInput::open(name, &config);
  } else if ((in = OIIO::ImageInput::create(format, false, &config))) {
    OIIO::ImageSpec opened;
    if (!in->open(name, opened, config)) {
      throw makeError(name, ": cannot read image as ", format, ": ", oneLine(in->geterror()));
    }
  }
  if (!in) throw makeError(name, ": cannot read image: ", oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw makeError(name, ": zero-size image (", spec.width, "x", spec.height, "x", spec.nchannels, ")");
  }
  if (spec.deep) throw makeError(name, ": deep images are not supported");
  if (spec.nchannels > 4) throw makeError(name, ": ", spec.nchannels, " channels; expected 1 to 4");
  checkPixelBudget(name, spec.width, spec.height, spec.nchannels, 0, memory_budget);
  const int channels = spec.nchannels;
  Image& img = out->image;
  img.width = spec.width;
  img.height = spec.height;
  img.channels = channels;
  img.pixels.assign(static_cast<std::size_t>(spec.width) * spec.height * channels, 0.0f);
  // OIIO's TIFF reader reports a truncated strip through geterror() yet returns true, the
  // missing rows left black: any error it recorded refuses the image.
  const bool read = in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img.pixels.data());
  if (const std::string error = in->geterror(); !read || !error.empty()) {
    throw makeError(name, ": cannot read pixels (truncated or corrupt?): ", oneLine(error));
  }
  const bool associated =
      img.hasAlpha() && spec.alpha_channel == channels - 1 && spec.get_int_attribute("oiio:UnassociatedAlpha", 0) == 0;
  if (associated) {  // EXR and friends store premultiplied colour: undo it.
    for (std::size_t p = 0; p < img.pixels.size(); p += channels) {
      const float a = img.pixels[p + channels - 1];
      if (a > 0.0f) {
        for (int c = 0; c < channels - 1; ++c) img.pixels[p + c] /= a;
      }
    }
  }
  out->info.depth = depthOf(spec.format);
  out->info.channels = channels;
  out->info.format = in->format_name();
  out->info.alpha_only = channels == 1 && spec.alpha_channel == 0;
  in->close();
}

std::string encode(const Image& img, const std::string& name, PixelDepth depth, bool smallest) {
  auto out = OIIO::ImageOutput::create(name);
  if (!out) {
    (void)OIIO::geterror();
    throw makeError(name, ": no OpenImageIO writer for this extension");
  }
  const std::string format = out->format_name();
  if (!out->supports("ioproxy")) throw makeError(name, ": format '", format, "' cannot be written to memory");
  if (img.hasAlpha() && !out->supports("alpha")) {
    throw makeError(name, ": format '", format, "' cannot store alpha; composite over white first or use PNG/TIFF/EXR");
  }
  const OIIO::TypeDesc type = typeOf(depth);
  OIIO::ImageSpec spec(img.width, img.height, img.channels, type);
  if (img.channels == 2) spec.channelnames = {"Y", "A"};  // so readers see grey + alpha
  if (img.hasAlpha()) {
    spec.alpha_channel = img.channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  if (smallest) spec.attribute("compression", format == "openexr" ? "zips" : "zip");
  const QuietStderr quiet;
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  void* proxy_ptr = &proxy;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_ptr);
  if (!out->open(name, spec)) throw makeError(name, ": cannot encode: ", oneLine(out->geterror()));
  bool ok = false;
  if (img.hasAlpha() && format == "openexr") {
    // OpenEXR stores premultiplied colour by definition (its writer ignores the
    // unassociated hint); load() divides it back out.
    std::vector<float> premultiplied(img.pixels);
    for (std::size_t p = 0; p < premultiplied.size(); p += img.channels) {
      for (int c = 0; c + 1 < img.channels; ++c) premultiplied[p + c] *= premultiplied[p + img.channels - 1];
    }
    ok = out->write_image(OIIO::TypeDesc::FLOAT, premultiplied.data());
  } else if (type.is_floating_point()) {
    ok = out->write_image(OIIO::TypeDesc::FLOAT, img.pixels.data());
  } else if (depth == PixelDepth::UInt16) {
    // Rounded to the stored integer here so every writer gets exact codes.
    std::vector<std::uint16_t> codes(img.pixels.size());
    std::transform(img.pixels.begin(), img.pixels.end(), codes.begin(),
                   [](float v) { return static_cast<std::uint16_t>(sampleCode(v, 65535)); });
    ok = out->write_image(OIIO::TypeDesc::UINT16, codes.data());
  } else {
    std::vector<std::uint8_t> codes(img.pixels.size());
    std::transform(img.pixels.begin(), img.pixels.end(), codes.begin(),
                   [](float v) { return static_cast<std::uint8_t>(sampleCode(v, 255)); });
    ok = out->write_image(OIIO::TypeDesc::UINT8, codes.data());
  }
  if (!ok || !out->close()) throw makeError(name, ": cannot encode: ", oneLine(out->geterror()));
  return std::string(bytes.begin(), bytes.end());
}

template <typename Work>
std::string guarded(const std::string& name, Work&& work) {
  try {
    work();
    return {};
  } catch (const std::bad_alloc&) {
    return name + ": out of memory";
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string loadEntry(const std::string& path, const std::string& format, std::uintmax_t memory_budget, Decoded* out) {
  return guarded(path, [&] { load(path, format, memory_budget, out); });
}

std::string encodeEntry(const Image& img, const std::string& path, PixelDepth depth, bool smallest,
                        std::string* bytes) {
  return guarded(path, [&] { *bytes = encode(img, path, depth, smallest); });
}

}  // namespace
}  // namespace shanshui::image::detail

extern "C" __attribute__((visibility("default"))) const shanshui::image::detail::OiioCodec* shanshui_oiio_codec() {
  static const shanshui::image::detail::OiioCodec codec = {
      shanshui::image::detail::kOiioCodecAbi, shanshui::image::detail::loadEntry, shanshui::image::detail::encodeEntry};
  return &codec;
}
