// Binary PGM/PPM (P5 grey, P6 RGB), 8 and 16 bits, by hand: the format is a text header
// and raw samples, and OpenImageIO 2.4 gets its 16-bit case wrong both ways (it reads 65535
// as 65534 and writes samples in the wrong byte order). ASCII and bitmap PNM (P1-P4) are
// left to OpenImageIO, once their body is known to be long enough for their header.
#include <algorithm>
#include <fstream>
#include <limits>
#include <vector>

#include "codecs.h"
#include "shanshui/core/error.h"

namespace shanshui::image::detail {

void checkTextPnmBody(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  std::string magic(2, '\0');
  if (!in.read(magic.data(), 2) || magic[0] != 'P' || magic[1] < '1' || magic[1] > '4') return;
  // Width, height (and maxval for P2, P3), separated by blanks and # comments; a header
  // that does not parse is left to the decoder to refuse.
  const int kind = magic[1] - '0', count = kind == 2 || kind == 3 ? 3 : 2;
  long long fields[3] = {};
  for (int k = 0; k < count; ++k) {
    while (in >> std::ws && in.peek() == '#') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    if (!(in >> fields[k])) return;
  }
  const long long width = fields[0], height = fields[1];
  if (width <= 0 || height <= 0 || width > (1LL << 31) || height > (1LL << 31)) return;
  const std::uintmax_t samples = static_cast<std::uintmax_t>(width) * static_cast<std::uintmax_t>(height) *
                                 static_cast<std::uintmax_t>(kind == 3 ? 3 : 1);
  const std::uintmax_t least = kind == 4   ? (static_cast<std::uintmax_t>(width) + 7) / 8 * height
                               : kind == 1 ? samples
                                           : 2 * samples - 1;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const std::streamoff at = in.tellg();
  const std::uintmax_t body = !ec && at > 0 && size > static_cast<std::uintmax_t>(at) ? size - at : 0;
  checkBodyCanHold(name, body, least, 1, "PNM");
}

Decoded readBinaryPnm(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  std::string magic(2, '\0');
  if (!in.read(magic.data(), 2) || (magic != "P5" && magic != "P6")) {
    throw makeError(name, ": not a binary PGM/PPM (P5 or P6)");
  }
  Decoded out;
  // Width, height and maxval, separated by blanks and # comments.
  long long fields[3] = {};
  for (long long& f : fields) {
    while (in >> std::ws && in.peek() == '#') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    if (!(in >> f)) throw makeError(name, ": PNM header: expected width, height and maximum value");
  }
  const long long width = fields[0], height = fields[1], maxval = fields[2];
  if (width <= 0 || height <= 0) throw makeError(name, ": zero-size image (", width, "x", height, ")");
  // Each side below 2^31, so that the products below stay within 64 bits.
  if (width > (1LL << 31) || height > (1LL << 31)) {
    throw makeError(name, ": PNM of ", width, " x ", height, " pixels; expected sides under 2147483648");
  }
  if (maxval < 1 || maxval > 65535) {
    throw makeError(name, ": PNM maximum value ", maxval, " is outside 1..65535");
  }
  in.get();  // the single blank after maxval
  const int channels = magic == "P5" ? 1 : 3;
  const int bytes_per_sample = maxval > 255 ? 2 : 1;
  if (width * height > kMaxImagePixels) checkPixelBudget(name, width, height, channels, 0, memoryBudget());
  {
    // Uncompressed: the body must hold every sample.
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    const auto header = static_cast<std::uintmax_t>(in.tellg());
    checkBodyCanHold(name, size > header ? size - header : 0,
                     static_cast<std::uintmax_t>(width) * height * channels * bytes_per_sample, 1, "PNM");
  }
  checkPixelBudget(name, width, height, channels,
                   static_cast<std::uintmax_t>(width) * height * channels * bytes_per_sample, memoryBudget());
  out.image = Image(static_cast<int>(width), static_cast<int>(height), channels);
  const std::size_t n = out.image.pixels.size();
  std::vector<unsigned char> raw(n * bytes_per_sample);
  if (!in.read(reinterpret_cast<char*>(raw.data()), static_cast<std::streamsize>(raw.size()))) {
    throw makeError(name, ": truncated PNM: expected ", n, " samples of ", 8 * bytes_per_sample, " bits");
  }
  std::vector<float> table(static_cast<std::size_t>(maxval) + 1);
  for (std::size_t c = 0; c < table.size(); ++c) table[c] = static_cast<float>(static_cast<double>(c) / maxval);
  for (std::size_t i = 0; i < n; ++i) {
    const long code = bytes_per_sample == 2 ? raw[2 * i] << 8 | raw[2 * i + 1] : raw[i];
    out.image.pixels[i] = table[std::min<long>(code, maxval)];
  }
  out.info.depth = bytes_per_sample == 2 ? PixelDepth::UInt16 : PixelDepth::UInt8;
  out.info.channels = channels;
  out.info.format = "pnm";
  return out;
}

std::string encodePnm(const Image& img, const std::string& name, PixelDepth depth) {
  SHANSHUI_CHECK(depth == PixelDepth::UInt8 || depth == PixelDepth::UInt16);
  if (img.channels != 1 && img.channels != 3) {
    throw makeError(name, ": PNM stores grey or RGB; the image has ", img.channels, " channels");
  }
  const bool wide = depth == PixelDepth::UInt16;
  std::string out = std::string(img.channels == 1 ? "P5" : "P6") + "\n" + std::to_string(img.width) + " " +
                    std::to_string(img.height) + (wide ? "\n65535\n" : "\n255\n");
  const std::size_t header = out.size();
  out.resize(header + (wide ? 2 : 1) * img.pixels.size());
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    if (wide) {
      const unsigned code = sampleCode(img.pixels[i], 65535);
      out[header + 2 * i] = static_cast<char>(code >> 8);
      out[header + 2 * i + 1] = static_cast<char>(code & 0xff);
    } else {
      out[header + i] = static_cast<char>(sampleCode(img.pixels[i], 255));
    }
  }
  return out;
}

}  // namespace shanshui::image::detail
