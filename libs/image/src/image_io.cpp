#include "shanshui/image/image_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string_view>

#include "codecs.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/core/module.h"

namespace shanshui::image {
namespace fs = std::filesystem;

double normalisationScale(PixelDepth depth) {
  switch (depth) {
    case PixelDepth::UInt8:
      return 255.0;
    case PixelDepth::UInt16:
      return 65535.0;
    case PixelDepth::Int16:
      return 32767.0;
    case PixelDepth::UInt32:
      return 4294967295.0;
    case PixelDepth::Int32:
      return 2147483647.0;
    default:
      return 1.0;
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
    case PixelDepth::UInt8:
      return "8";
    case PixelDepth::UInt16:
      return "16";
    case PixelDepth::Int16:
      return "int16";
    case PixelDepth::UInt32:
      return "uint32";
    case PixelDepth::Int32:
      return "int32";
    case PixelDepth::Half:
      return "half";
    case PixelDepth::Float:
      return "float";
    case PixelDepth::Double:
      return "double";
  }
  return "?";
}

namespace detail {

namespace {

constexpr const char* kModuleName = "libshanshui_image_oiio.so";

struct LoadedModule {
  const OiioCodec* codec = nullptr;
  std::string error;
};

// Looks for the module in $SHANSHUI_IMAGE_MODULE (a file), next to the running program,
// then in the build tree it was built in.
LoadedModule loadModule() {
#ifdef SHANSHUI_IMAGE_MODULE_DIR
  const std::string build_dir = SHANSHUI_IMAGE_MODULE_DIR;
#else
  const std::string build_dir;
#endif
  LoadedModule result;
  using Entry = const OiioCodec* (*)();
  auto entry = reinterpret_cast<Entry>(
      loadModuleEntry(kModuleName, "SHANSHUI_IMAGE_MODULE", build_dir, "shanshui_oiio_codec", result.error));
  const OiioCodec* codec = entry ? entry() : nullptr;
  if (entry && (codec == nullptr || codec->abi_version != kOiioCodecAbi)) {
    result.error = std::string(kModuleName) + " is not this build's codec module";
    return result;
  }
  result.codec = codec;
  return result;
}

}  // namespace

const OiioCodec& oiioCodec(const std::string& name, const std::string& purpose) {
  static const LoadedModule loaded = loadModule();
  if (loaded.codec == nullptr) {
    throw makeError(name, ": ", purpose, " needs the OpenImageIO module ", kModuleName, ": ", loaded.error);
  }
  return *loaded.codec;
}

}  // namespace detail

namespace {

enum class Codec { Png, Jpeg, Pnm, Module };

struct Sniffed {
  Codec codec = Codec::Module;
  std::string format;  //!< the module's reader the first bytes name; empty: the extension's
};

// The codec for a file's first bytes; a format without a signature (Targa) goes by its
// extension.
Sniffed sniff(const fs::path& path) {
  std::array<unsigned char, 4> m{};
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(m.data()), m.size());
  const auto got = in.gcount();
  auto is = [&](std::string_view sig) {
    if (got < static_cast<std::streamsize>(sig.size())) return false;
    for (std::size_t i = 0; i < sig.size(); ++i)
      if (m[i] != static_cast<unsigned char>(sig[i])) return false;
    return true;
  };
  using namespace std::string_view_literals;
  if (is("\x89PNG"sv)) return {Codec::Png, {}};
  if (is("\xFF\xD8\xFF"sv)) return {Codec::Jpeg, {}};
  if (is("P5"sv) || is("P6"sv)) return {Codec::Pnm, {}};
  if (is("II*\0"sv) || is("MM\0*"sv)) return {Codec::Module, "tiff"};
  if (is("\x76\x2F\x31\x01"sv)) return {Codec::Module, "openexr"};
  if (is("GIF8"sv)) return {Codec::Module, "gif"};
  if (is("BM"sv)) return {Codec::Module, "bmp"};
  if (is("#?"sv)) return {Codec::Module, "hdr"};
  if (is("P1"sv) || is("P2"sv) || is("P3"sv) || is("P4"sv)) return {Codec::Module, "pnm"};
  return {};
}

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// OpenImageIO's name of the format written for `path`'s extension; empty when unknown.
std::string formatOf(const fs::path& path) {
  static const std::array<std::pair<const char*, const char*>, 12> kFormats = {{{".png", "png"},
                                                                                {".jpg", "jpeg"},
                                                                                {".jpeg", "jpeg"},
                                                                                {".tif", "tiff"},
                                                                                {".tiff", "tiff"},
                                                                                {".exr", "openexr"},
                                                                                {".pgm", "pnm"},
                                                                                {".ppm", "pnm"},
                                                                                {".pnm", "pnm"},
                                                                                {".bmp", "bmp"},
                                                                                {".tga", "targa"},
                                                                                {".hdr", "hdr"}}};
  const std::string ext = lowerExtension(path);
  for (const auto& [e, format] : kFormats) {
    if (ext == e) return format;
  }
  return {};
}

bool storesDepth(const std::string& format, PixelDepth depth) {
  if (depth == PixelDepth::UInt8) return true;
  if (format == "tiff") return true;
  if (format == "openexr") return true;  // integer samples are stored as half floats
  if (format == "png" || format == "pnm") return depth == PixelDepth::UInt16;
  return false;
}

}  // namespace

Image loadImage(const fs::path& path, ImageInfo* info) {
  const std::string name = path.string();
  checkInputFile(path, "an image");
  detail::Decoded decoded;
  const Sniffed sniffed = sniff(path);
  switch (sniffed.codec) {
    case Codec::Png:
      decoded = detail::readPng(path);
      break;
    case Codec::Jpeg:
      decoded = detail::readJpeg(path);
      break;
    case Codec::Pnm:
      decoded = detail::readBinaryPnm(path);
      break;
    case Codec::Module: {
      if (sniffed.format == "pnm") detail::checkTextPnmBody(path);  // before OpenImageIO allocates for it
      const std::string error =
          detail::oiioCodec(name, "reading this format").load(name, sniffed.format, memoryBudget(), &decoded);
      if (!error.empty()) throw Error(error);
      // Integer codes decode to finite values; float formats (EXR, TIFF, HDR) may not.
      for (float v : decoded.image.pixels) {
        if (!std::isfinite(v)) throw makeError(name, ": contains NaN or infinite pixel values");
      }
      break;
    }
  }
  if (info) *info = decoded.info;
  return std::move(decoded.image);
}

const std::vector<std::string>& writableImageExtensions() {
  static const std::vector<std::string> list = {".png", ".jpg", ".jpeg", ".tif", ".tiff", ".exr",
                                                ".pgm", ".ppm", ".pnm",  ".bmp", ".tga",  ".hdr"};
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
  if (img.channels < 1 || img.channels > 4) {
    throw makeError(name, ": refusing to write ", img.channels, " channels; expected 1 to 4");
  }
  for (float v : img.pixels) {
    if (!std::isfinite(v)) throw makeError(name, ": refusing to write an image with NaN or infinite values");
  }
  const std::string format = formatOf(path);
  if (format.empty()) {
    throw makeError(name, ": unknown image format for extension '", path.extension().string(),
                    "' (expected .png, .jpg, .tif, .exr, ...)");
  }
  if (!storesDepth(format, depth)) {
    const std::string what = depth == PixelDepth::UInt16 ? "16-bit" : depthName(depth);
    throw makeError(name, ": format '", format, "' cannot store ", what,
                    " samples; use .tif (any depth), .png (8 or 16 bits) or .exr (float)");
  }
  if ((format == "jpeg" || format == "pnm") && img.hasAlpha()) {
    throw makeError(name, ": format '", format, "' cannot store alpha; composite over white first or use PNG/TIFF/EXR");
  }
  if (format == "png") return detail::encodePng(img, name, depth, options.smallest);
  if (format == "jpeg") return detail::encodeJpeg(img, name);
  if (format == "pnm") return detail::encodePnm(img, name, depth);
  std::string bytes;
  const std::string error =
      detail::oiioCodec(name, "writing this format").encode(img, name, depth, options.smallest, &bytes);
  if (!error.empty()) throw Error(error);
  return bytes;
}

void saveImage(const Image& img, const fs::path& path, PixelDepth depth, const WriteOptions& options) {
  checkOutputPath(path);
  writeFileAtomically(path, encodeImage(img, path, depth, options));
}

}  // namespace shanshui::image
