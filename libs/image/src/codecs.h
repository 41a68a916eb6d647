// The image codecs behind image_io.cpp (internal to libs/image).
//
// PNG, JPEG and binary PNM are read and written here with libpng, libjpeg and a few lines
// of code, so a tool that touches only those formats loads a handful of shared libraries.
// Every other format goes through OpenImageIO, whose dependency closure is ~260 shared
// libraries (FFmpeg, DCMTK, OpenVDB, GStreamer, ...) and ~0.25 s of start-up: it lives in a
// module (libshanshui_image_oiio.so) loaded the first time such a file is met.
#pragma once

#include <filesystem>
#include <string>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/image/image_io.h"

namespace shanshui::image::detail {

//! A decoded file: pixels normalised as loadImage() documents, and what the file held.
struct Decoded {
  Image image;
  ImageInfo info;
};

//! What decoding an image takes: its float pixels and `buffer_bytes` the decoder holds beside.
inline std::uintmax_t decodedBytes(long long width, long long height, int channels, std::uintmax_t buffer_bytes) {
  return static_cast<std::uintmax_t>(width) * static_cast<std::uintmax_t>(height) * channels * sizeof(float) +
         buffer_bytes;
}

//! Refuses an image before anything is allocated: width x height above kMaxImagePixels, or
//! decodedBytes() over `budget` (memoryBudget() in the programs; the OpenImageIO module gets it
//! as an argument), so a 100000 x 100000 header with a tiny body is an error naming the
//! file, not bad_alloc.
inline void checkPixelBudget(const std::string& name, long long width, long long height, int channels,
                             std::uintmax_t buffer_bytes, std::uintmax_t budget) {
  if (width * height > kMaxImagePixels) {
    throw makeError(name, ": ", width, "x", height, " pixels is more than the limit of ", kMaxImagePixels,
                    " (16384 x 16384)");
  }
  const std::uintmax_t need = decodedBytes(width, height, channels, buffer_bytes);
  if (need > budget) {
    throw makeError(name, ": decoding this image (", width, "x", height, ", ", channels, " channels) needs ",
                    byteCount(need), ", more than the memory budget of ", byteCount(budget),
                    " (--max-memory or SHANSHUI_MAX_MEMORY sets it)");
  }
}

//! Refuses a file too short to hold the `raw_bytes` its header promises even at the
//! format's best compression ratio (`max_ratio` bytes out per byte in): it must be cut
//! short or corrupt, and saying so now saves allocating and inflating what is not there.
inline void checkBodyCanHold(const std::string& name, std::uintmax_t file_bytes, std::uintmax_t raw_bytes,
                             std::uintmax_t max_ratio, const char* format) {
  if (file_bytes * max_ratio < raw_bytes) {
    throw makeError(name, ": truncated or corrupt ", format, ": its header promises ", raw_bytes,
                    " bytes of pixels, more than its ", file_bytes, " bytes can hold at ", max_ratio,
                    " to 1 compression");
  }
}

// Each reader throws Error naming `path` for a truncated, corrupt or unsupported file.
Decoded readPng(const std::filesystem::path& path);
Decoded readJpeg(const std::filesystem::path& path);
//! ASCII and bitmap PNM (P1-P4, which OpenImageIO decodes): throws Error naming `path` when
//! the body is too short for what the header promises (P4 a bit a pixel; P1 a character;
//! P2, P3 a digit and a blank a sample), before a decoder allocates for it.
void checkTextPnmBody(const std::filesystem::path& path);
//! Binary PNM (P5 grey, P6 RGB), 8 or 16 bits.
Decoded readBinaryPnm(const std::filesystem::path& path);

// Each encoder gets pixels already checked (non-empty, finite) and a depth the format stores.
std::string encodePng(const Image& img, const std::string& name, PixelDepth depth, bool smallest);
std::string encodeJpeg(const Image& img, const std::string& name);
std::string encodePnm(const Image& img, const std::string& name, PixelDepth depth);

//! Clamps to [0,1] and rounds to the integer code of an 8- or 16-bit sample.
inline unsigned sampleCode(float v, unsigned max_code) {
  const double c = v < 0.0f ? 0.0 : (v > 1.0f ? 1.0 : static_cast<double>(v));
  return static_cast<unsigned>(c * max_code + 0.5);
}

// ---- the OpenImageIO module -------------------------------------------------------------

//! What libshanshui_image_oiio.so exports (by `shanshui_oiio_codec`). Errors come back as
//! a message (empty on success), so no exception crosses the module boundary.
struct OiioCodec {
  int abi_version;
  //! `format`: the OpenImageIO reader the file's first bytes named ("tiff", "openexr"), or
  //! empty for the one its extension names; no other reader is tried.
  std::string (*load)(const std::string& path, const std::string& format, std::uintmax_t memory_budget, Decoded* out);
  std::string (*encode)(const Image& img, const std::string& path, PixelDepth depth, bool smallest, std::string* bytes);
};
constexpr int kOiioCodecAbi = 3;

//! The module, loaded on first use; throws Error naming `name` and what it was for when
//! the module cannot be found or loaded.
const OiioCodec& oiioCodec(const std::string& name, const std::string& purpose);

}  // namespace shanshui::image::detail
