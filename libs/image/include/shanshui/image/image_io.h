// Loading and saving images: PNG, JPEG and binary PGM/PPM directly (libpng, libjpeg), every
// other format (TIFF, EXR, GIF read, BMP, ...) through OpenImageIO in a module loaded on
// first use (src/codecs.h says why).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "shanshui/image/image.h"

namespace shanshui::image {

//! Sample type of a file. Integer data are normalised on load (value / max of the type:
//! 255, 65535, 32767, ...); normalisationScale() gives the factor back to raw values.
enum class PixelDepth { UInt8, UInt16, Int16, UInt32, Int32, Half, Float, Double };

struct ImageInfo {
  PixelDepth depth = PixelDepth::UInt8;
  int channels = 0;
  std::string format;       //!< OpenImageIO format name: "png", "tiff", "openexr", ...
  bool alpha_only = false;  //!< the file's only channel is alpha (a mask, not an image)
};

//! Factor that turns a loaded (normalised) value back into the file's raw integer value;
//! 1 for floating-point data.
double normalisationScale(PixelDepth depth);

//! The depth names accepted on command lines: "8", "16", "float".
PixelDepth parseDepth(const std::string& text);
const char* depthName(PixelDepth depth);

//! Loads the first subimage. Throws Error naming the file for a missing, unreadable,
//! truncated, zero-size or unsupported file.
Image loadImage(const std::filesystem::path& path, ImageInfo* info = nullptr);

//! Largest image read or written: 16384 x 16384 pixels. A header asking for more is refused
//! before any allocation.
constexpr long long kMaxImagePixels = 16384LL * 16384LL;

//! Extensions saveImage() writes, lower case with the dot: for OutputSet::declare().
const std::vector<std::string>& writableImageExtensions();

struct WriteOptions {
  bool smallest = false;  //!< slowest, smallest compression (PNG level 9); default is fast (level 1)
};

//! The file's bytes for the format given by `path`'s extension (the file is not touched).
//! 16-bit and float depths are refused for formats that cannot store them (JPEG: 8 bits);
//! values are clamped to [0,1] and rounded for integer depths.
std::string encodeImage(const Image& img, const std::filesystem::path& path, PixelDepth depth = PixelDepth::UInt8,
                        const WriteOptions& options = {});

//! The depth nearest to `wanted` that the format of `path` can store (JPEG: 8; PNG: 8 or 16;
//! TIFF, EXR: all), for a tool's default when the user named no depth.
PixelDepth closestDepth(const std::filesystem::path& path, PixelDepth wanted);

//! Saves with the format given by the extension and the requested depth (8, 16 or float;
//! see encodeImage). Values are clamped to
//! [0,1] for integer depths. Writes atomically: on failure nothing replaces `path`.
//! Throws Error for an empty image, NaN/Inf pixels or an unknown extension.
void saveImage(const Image& img, const std::filesystem::path& path, PixelDepth depth = PixelDepth::UInt8,
               const WriteOptions& options = {});

}  // namespace shanshui::image
