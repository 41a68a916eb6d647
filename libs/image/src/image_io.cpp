#include "shanshui/image/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
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

namespace {

// Refuses a file whose header promises more pixels than the budget before anything is
// allocated for it, so a 100000 x 100000 header with a tiny body is an error, not bad_alloc.
void checkPixelBudget(const std::string& name, long long width, long long height, long long channels) {
  if (width * height > kMaxImagePixels) {
    throw makeError(name, ": ", width, "x", height, " pixels is more than the limit of ", kMaxImagePixels,
                    " (16384 x 16384)");
  }
  (void)channels;
}

// libpng prints "libpng error: ..." to stderr itself before OpenImageIO reports the same
// error; while a file is decoded or encoded, stderr goes to a scratch file so the tool's
// one line is the only one. (The same text is in OpenImageIO's error message.)
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

// libjpeg decodes a cut file to the end, filling the missing rows with grey and only
// warning; a complete JPEG ends with the EOI marker (FF D9), possibly followed by padding.
void checkJpegComplete(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 4096);
  std::string bytes(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(bytes.data(), tail);
  if (bytes.find("\xFF\xD9") == std::string::npos) {
    throw makeError(path.string(), ": truncated JPEG (no end-of-image marker)");
  }
}

// OpenImageIO 2.4's PNM reader scales 16-bit samples by 65535 / 65536 (65535 arrives as
// 65534), so binary 16-bit PGM/PPM (P5/P6, maxval > 255) is decoded here: a header of
// magic, width, height and maxval separated by blanks or # comments, then big-endian samples.
bool readPnm16(const fs::path& path, Image& img) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  in >> magic;
  if (magic != "P5" && magic != "P6") return false;
  long long fields[3] = {};
  for (long long& f : fields) {
    while (in >> std::ws && in.peek() == '#') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    if (!(in >> f)) return false;
  }
  const long long maxval = fields[2];
  if (maxval <= 255 || maxval > 65535 || fields[0] != img.width || fields[1] != img.height) return false;
  in.get();  // the single blank after maxval
  const std::size_t n = img.pixels.size();
  std::vector<unsigned char> raw(2 * n);
  if (!in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size()))) {
    throw makeError(path.string(), ": truncated PNM: expected ", n, " 16-bit samples");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const int code = raw[2 * i] << 8 | raw[2 * i + 1];
    img.pixels[i] = static_cast<float>(std::min<double>(code, maxval) / maxval);
  }
  return true;
}

// The writer's counterpart: OpenImageIO 2.4 writes 16-bit PNM samples in the wrong byte
// order, so binary 16-bit PGM (grey) and PPM (RGB) are encoded here, big-endian as the
// format specifies.
std::string pnm16Bytes(const Image& img, const std::string& name) {
  if (img.channels != 1 && img.channels != 3) {
    throw makeError(name, ": PNM stores grey or RGB; the image has ", img.channels, " channels");
  }
  std::string out = std::string(img.channels == 1 ? "P5" : "P6") + "\n" + std::to_string(img.width) + " " +
                    std::to_string(img.height) + "\n65535\n";
  const std::size_t header = out.size();
  out.resize(header + 2 * img.pixels.size());
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const long code = std::lround(std::clamp(img.pixels[i], 0.0f, 1.0f) * 65535.0);
    out[header + 2 * i] = static_cast<char>(code >> 8);
    out[header + 2 * i + 1] = static_cast<char>(code & 0xff);
  }
  return out;
}

}  // namespace

Image loadImage(const fs::path& path, ImageInfo* info) {
  const std::string name = path.string();
  checkInputFile(path, "an image");

  const QuietStderr quiet;
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
  checkPixelBudget(name, spec.width, spec.height, spec.nchannels);
  if (std::string(in->format_name()) == "jpeg") checkJpegComplete(path);
  const int channels = spec.nchannels;
  Image img(spec.width, spec.height, channels);
  const bool pnm16 = std::string(in->format_name()) == "pnm" && spec.format == OIIO::TypeDesc::UINT16;
  if (pnm16 && readPnm16(path, img)) {
    // decoded by readPnm16
  } else if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, img.pixels.data())) {
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


namespace {

bool storesDepth(const std::string& format, PixelDepth depth) {
  if (depth == PixelDepth::UInt8) return true;
  if (format == "tiff") return true;
  if (format == "openexr") return true;  // integer samples are stored as half floats
  if (format == "png" || format == "pnm") return depth == PixelDepth::UInt16;
  return false;
}

std::string formatOf(const fs::path& path) {
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out) {
    (void)OIIO::geterror();
    return {};
  }
  return out->format_name();
}

}  // namespace

const std::vector<std::string>& writableImageExtensions() {
  static const std::vector<std::string> list = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".exr",
                                                ".pgm", ".ppm", ".pnm", ".bmp", ".tga", ".hdr"};
  return list;
}

PixelDepth closestDepth(const fs::path& path, PixelDepth wanted) {
  const std::string format = formatOf(path);
  if (storesDepth(format, wanted)) return wanted;
  if (format == "openexr") return PixelDepth::Float;
  const bool wide = wanted != PixelDepth::UInt8;
  if (wide && storesDepth(format, PixelDepth::UInt16)) return PixelDepth::UInt16;
  return PixelDepth::UInt8;
}

std::string encodeImage(const Image& img, const fs::path& path, PixelDepth depth, const WriteOptions& options) {
  const std::string name = path.string();
  if (img.empty() || img.width <= 0 || img.height <= 0) {
    throw makeError(name, ": refusing to write an empty image (", img.width, "x", img.height, ")");
  }
  for (float v : img.pixels) {
    if (!std::isfinite(v)) throw makeError(name, ": refusing to write an image with NaN or infinite values");
  }
  auto out = OIIO::ImageOutput::create(name);
  if (!out) {
    (void)OIIO::geterror();
    throw makeError(name, ": unknown image format for extension '", path.extension().string(),
                    "' (expected .png, .jpg, .tif, .exr, ...)");
  }
  const std::string format = out->format_name();
  OIIO::TypeDesc type = typeOf(depth);
  if (!storesDepth(format, depth)) {
    const std::string what = depth == PixelDepth::UInt16 ? "16-bit" : depthName(depth);
    throw makeError(name, ": format '", format, "' cannot store ", what,
                    " samples; use .tif (any depth), .png (8 or 16 bits) or .exr (float)");
  }
  if (!out->supports("ioproxy")) throw makeError(name, ": format '", format, "' cannot be written to memory");
  OIIO::ImageSpec spec(img.width, img.height, img.channels, type);
  if (img.channels == 2) spec.channelnames = {"Y", "A"};  // so readers see grey + alpha
  if (img.hasAlpha()) {
    spec.alpha_channel = img.channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  if (img.hasAlpha() && !out->supports("alpha")) {
    throw makeError(name, ": format '", format, "' cannot store alpha; composite over white first or use PNG/TIFF/EXR");
  }
  spec.attribute("png:compressionLevel", options.smallest ? 9 : 1);
  if (options.smallest) spec.attribute("compression", format == "openexr" ? "zips" : "zip");
  if (format == "pnm" && depth == PixelDepth::UInt16) return pnm16Bytes(img, name);
  const QuietStderr quiet;
  // Encoded into memory; the caller writes the bytes with checked system calls.
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  void* proxyPtr = &proxy;
  spec.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxyPtr);
  if (!out->open(name, spec)) {
    throw makeError(name, ": cannot encode: ", oneLine(out->geterror()));
  }
  bool ok = false;
  if (img.hasAlpha() && format == "openexr") {
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
    // Rounded to the stored integer here (OIIO's float conversion would do the same) so
    // every writer, PNM included, gets exact codes.
    const double scale = normalisationScale(depth);
    if (depth == PixelDepth::UInt16) {
      std::vector<std::uint16_t> codes(img.pixels.size());
      std::transform(img.pixels.begin(), img.pixels.end(), codes.begin(), [&](float v) {
        return static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * scale));
      });
      ok = out->write_image(OIIO::TypeDesc::UINT16, codes.data());
    } else {
      std::vector<std::uint8_t> codes(img.pixels.size());
      std::transform(img.pixels.begin(), img.pixels.end(), codes.begin(), [&](float v) {
        return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0));
      });
      ok = out->write_image(OIIO::TypeDesc::UINT8, codes.data());
    }
  }
  if (!ok || !out->close()) throw makeError(name, ": cannot encode: ", oneLine(out->geterror()));
  return std::string(bytes.begin(), bytes.end());
}

void saveImage(const Image& img, const fs::path& path, PixelDepth depth, const WriteOptions& options) {
  checkOutputPath(path);
  writeFileAtomically(path, encodeImage(img, path, depth, options));
}

}  // namespace shanshui::image
