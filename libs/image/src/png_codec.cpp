// PNG: read with libpng 1.6; written by a parallel encoder over ISA-L (16-bit samples) or
// zlib (8-bit) by default, or by libpng at its smallest (--smallest). libpng reports errors by longjmp: every call that
// can fail runs in a small function of its own that holds the setjmp and no C++ object, and the message is kept in the
// context so the caller throws one Error naming the file.
#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <exception>
#include <thread>
#include <vector>

#include <isa-l/igzip_lib.h>
#include <png.h>
#include <zlib.h>

#include "codecs.h"
#include "shanshui/core/error.h"

namespace shanshui::image::detail {
namespace {

struct PngContext {
  std::array<char, 256> message{};
  bool out_of_memory = false;
};

void onPngError(png_structp png, png_const_charp msg) {
  auto* ctx = static_cast<PngContext*>(png_get_error_ptr(png));
  std::snprintf(ctx->message.data(), ctx->message.size(), "%s", msg);
  png_longjmp(png, 1);
}

// Warnings (an sRGB profile libpng dislikes, a bad CRC in an ancillary chunk) do not stop
// the read and would be a second line on stderr: dropped.
void onPngWarning(png_structp, png_const_charp) {}

// PNG colour type by channel count (1 grey ... 4 RGBA).
constexpr std::array<int, 5> kColourType = {0, PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                            PNG_COLOR_TYPE_RGB_ALPHA};

// One row of samples as PNG stores them: 8-bit codes, or 16-bit codes big-endian.
void encodeRow(const float* src, std::size_t samples, int bits, png_byte* out) {
  if (bits == 16) {
    for (std::size_t i = 0; i < samples; ++i) {
      const unsigned code = sampleCode(src[i], 65535);
      out[2 * i] = static_cast<png_byte>(code >> 8);
      out[2 * i + 1] = static_cast<png_byte>(code & 0xff);
    }
  } else {
    for (std::size_t i = 0; i < samples; ++i) out[i] = static_cast<png_byte>(sampleCode(src[i], 255));
  }
}

// ---- reading ----------------------------------------------------------------------------

bool startRead(png_structp png, png_infop info, std::FILE* file) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_read_info(png, info);
  return true;
}

// Palette, low-bit grey and tRNS transparency become 8-bit grey/RGB with alpha; 16-bit
// samples stay 16-bit (big-endian, converted below).
bool configureRead(png_structp png, png_infop info, int* passes) {
  if (setjmp(png_jmpbuf(png))) return false;
  const int type = png_get_color_type(png, info);
  if (type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (type == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  *passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  return true;
}

bool readRows(png_structp png, png_bytepp rows, png_uint_32 count) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_rows(png, rows, nullptr, count);
  return true;
}

bool readImage(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  return true;
}

bool finishRead(png_structp png) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_end(png, nullptr);
  return true;
}

struct ReadHandles {
  png_structp png = nullptr;
  png_infop info = nullptr;
  std::FILE* file = nullptr;
  ~ReadHandles() {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    if (file) std::fclose(file);
  }
};

// Normalised value of every 8- and 16-bit code, so a row converts by table look-up.
const std::vector<float>& codeTable(int bits) {
  static const std::vector<float> table8 = [] {
    std::vector<float> t(256);
    for (int c = 0; c < 256; ++c) t[c] = static_cast<float>(c / 255.0);
    return t;
  }();
  static const std::vector<float> table16 = [] {
    std::vector<float> t(65536);
    for (int c = 0; c < 65536; ++c) t[c] = static_cast<float>(c / 65535.0);
    return t;
  }();
  return bits == 16 ? table16 : table8;
}

void convertRow(const png_byte* row, float* out, std::size_t samples, int bits) {
  const float* table = codeTable(bits).data();
  if (bits == 16) {
    for (std::size_t i = 0; i < samples; ++i) out[i] = table[row[2 * i] << 8 | row[2 * i + 1]];
  } else {
    for (std::size_t i = 0; i < samples; ++i) out[i] = table[row[i]];
  }
}

// ---- writing ----------------------------------------------------------------------------

struct WriteSink {
  std::string* bytes;
  bool failed = false;
};

void onPngWrite(png_structp png, png_bytep data, png_size_t size) {
  auto* sink = static_cast<WriteSink*>(png_get_io_ptr(png));
  try {
    sink->bytes->append(reinterpret_cast<const char*>(data), size);
  } catch (const std::bad_alloc&) {
    sink->failed = true;
  }
  if (sink->failed) png_error(png, "out of memory for the encoded file");
}

void onPngFlush(png_structp) {}

bool startWrite(png_structp png, png_infop info, WriteSink* sink, const Image& img, int bits) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, sink, onPngWrite, onPngFlush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height), bits,
               kColourType[img.channels], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // The smallest file: zlib level 9 and libpng's adaptive choice of filter per row.
  png_set_compression_level(png, 9);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_ALL_FILTERS);
  png_write_info(png, info);
  return true;
}

bool writeRow(png_structp png, png_bytep row) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_write_row(png, row);
  return true;
}

bool finishWrite(png_structp png, png_infop info) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_write_end(png, info);
  return true;
}

struct WriteHandles {
  png_structp png = nullptr;
  png_infop info = nullptr;
  ~WriteHandles() { png_destroy_write_struct(&png, info ? &info : nullptr); }
};

// ---- fast parallel writer -----------------------------------------------------------------
//
// The default PNG path: rows are converted and Sub-filtered, and bands of rows are deflated
// independently on every core. Each band is a raw deflate stream that ends on a byte boundary
// (Z_SYNC_FLUSH; the last band Z_FINISH), so the bands joined behind one zlib header, with
// the Adler-32 of all filtered bytes combined from the bands' own, form one valid zlib
// stream (the method of pigz). The band size is fixed, not the thread count, so the bytes
// are the same on every machine. The PNG container around it (signature, IHDR, IDAT, IEND
// with their CRCs) is written here; libpng has no parallel writer.

constexpr std::size_t kBandBytes = 1 << 20;  // filtered bytes per band, about
constexpr std::size_t kIdatBytes = 1 << 23;  // largest IDAT chunk written

struct Band {
  int first_row = 0;
  int rows = 0;
  std::string deflated;
  uLong adler = 0;
  std::size_t filtered_size = 0;
};

void putBigEndian32(std::string& out, std::uint32_t v) {
  const char bytes[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                         static_cast<char>(v)};
  out.append(bytes, 4);
}

void putChunk(std::string& out, const char* type, const char* data, std::size_t size) {
  putBigEndian32(out, static_cast<std::uint32_t>(size));
  const std::size_t start = out.size();
  out.append(type, 4);
  out.append(data, size);
  const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(out.data() + start), static_cast<uInt>(size + 4));
  putBigEndian32(out, static_cast<std::uint32_t>(crc));
}

// Deflates a band's filtered bytes with zlib at level 1 into band.deflated; false on error.
bool deflateWithZlib(const std::vector<Bytef>& filtered, bool last, Band& band, int* rc) {
  z_stream zs{};
  if (deflateInit2(&zs, 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return false;
  band.deflated.resize(deflateBound(&zs, static_cast<uLong>(filtered.size())) + 16);
  zs.next_in = const_cast<Bytef*>(filtered.data());
  zs.avail_in = static_cast<uInt>(filtered.size());
  zs.next_out = reinterpret_cast<Bytef*>(band.deflated.data());
  zs.avail_out = static_cast<uInt>(band.deflated.size());
  *rc = deflate(&zs, last ? Z_FINISH : Z_SYNC_FLUSH);
  const bool ok = last ? *rc == Z_STREAM_END : (*rc == Z_OK && zs.avail_in == 0 && zs.avail_out > 0);
  band.deflated.resize(zs.total_out);
  deflateEnd(&zs);
  return ok;
}

// The same with ISA-L's igzip at its level 1: on 16-bit samples, whose low bytes are mostly
// noise, 8x faster than zlib's fastest (Z_RLE) for a file of the same size (docs/io.md).
bool deflateWithIsal(std::vector<Bytef>& filtered, bool last, Band& band, int* rc) {
  isal_zstream zs;
  isal_deflate_init(&zs);
  std::vector<std::uint8_t> level_buffer(ISAL_DEF_LVL1_DEFAULT);
  zs.level = 1;
  zs.level_buf = level_buffer.data();
  zs.level_buf_size = static_cast<std::uint32_t>(level_buffer.size());
  // Room for stored blocks on incompressible input, plus the sync-flush marker.
  band.deflated.resize(filtered.size() + filtered.size() / 16 + 1024);
  zs.next_in = filtered.data();
  zs.avail_in = static_cast<std::uint32_t>(filtered.size());
  zs.next_out = reinterpret_cast<std::uint8_t*>(band.deflated.data());
  zs.avail_out = static_cast<std::uint32_t>(band.deflated.size());
  zs.end_of_stream = last ? 1 : 0;
  zs.flush = last ? NO_FLUSH : SYNC_FLUSH;
  *rc = isal_deflate(&zs);
  const bool ok = *rc == COMP_OK && zs.avail_in == 0 && (last ? zs.internal_state.state == ZSTATE_END : true);
  band.deflated.resize(zs.total_out);
  return ok;
}

// Filters and deflates one band; throws Error (with `name`) if the deflater fails.
void deflateBand(const Image& img, int bits, bool last, Band& band, const std::string& name) {
  const std::size_t samples = static_cast<std::size_t>(img.width) * img.channels;
  const std::size_t bytes_per_sample = bits / 8;
  const std::size_t row_bytes = samples * bytes_per_sample;
  const std::size_t bpp = img.channels * bytes_per_sample;  // Sub looks this many bytes back
  std::vector<Bytef> filtered((row_bytes + 1) * band.rows);
  std::vector<Bytef> raw(row_bytes);
  for (int r = 0; r < band.rows; ++r) {
    encodeRow(&img.pixels[static_cast<std::size_t>(band.first_row + r) * samples], samples, bits, raw.data());
    Bytef* out = &filtered[r * (row_bytes + 1)];
    out[0] = PNG_FILTER_VALUE_SUB;
    for (std::size_t i = 0; i < row_bytes; ++i) {
      out[1 + i] = static_cast<Bytef>(raw[i] - (i >= bpp ? raw[i - bpp] : 0));
    }
  }
  band.filtered_size = filtered.size();
  band.adler = adler32(adler32(0L, Z_NULL, 0), filtered.data(), static_cast<uInt>(filtered.size()));
  int rc = 0;
  // 8-bit samples (renders) stay with zlib's level 1: ISA-L's files are 13-15 % larger there.
  const bool ok = bits == 16 ? deflateWithIsal(filtered, last, band, &rc) : deflateWithZlib(filtered, last, band, &rc);
  if (!ok) throw makeError(name, ": cannot encode PNG: ", bits == 16 ? "ISA-L" : "zlib", " error ", rc);
}

std::string encodePngParallel(const Image& img, const std::string& name, int bits) {
  const std::size_t row_bytes = static_cast<std::size_t>(img.width) * img.channels * (bits / 8) + 1;
  const int rows_per_band = static_cast<int>(std::max<std::size_t>(1, kBandBytes / row_bytes));
  std::vector<Band> bands;
  for (int y = 0; y < img.height; y += rows_per_band) {
    Band band;
    band.first_row = y;
    band.rows = std::min(rows_per_band, img.height - y);
    bands.push_back(std::move(band));
  }
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(bands.size());
  auto work = [&] {
    for (std::size_t b = next++; b < bands.size(); b = next++) {
      try {
        deflateBand(img, bits, b + 1 == bands.size(), bands[b], name);
      } catch (...) {
        errors[b] = std::current_exception();
      }
    }
  };
  const unsigned threads = std::min<unsigned>(std::max(1u, std::thread::hardware_concurrency()), bands.size());
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }

  std::string stream = {'\x78', '\x01'};  // zlib header: deflate, 32 KiB window, fastest
  std::size_t total = 2 + 4;
  for (const Band& band : bands) total += band.deflated.size();
  stream.reserve(total);
  uLong adler = adler32(0L, Z_NULL, 0);
  for (const Band& band : bands) {
    stream += band.deflated;
    adler = adler32_combine(adler, band.adler, static_cast<z_off_t>(band.filtered_size));
  }
  putBigEndian32(stream, static_cast<std::uint32_t>(adler));

  std::string header;
  putBigEndian32(header, static_cast<std::uint32_t>(img.width));
  putBigEndian32(header, static_cast<std::uint32_t>(img.height));
  header += {static_cast<char>(bits), static_cast<char>(kColourType[img.channels]), 0, 0, 0};
  std::string png = "\x89PNG\r\n\x1a\n";
  png.reserve(stream.size() + stream.size() / kIdatBytes * 12 + 64);
  putChunk(png, "IHDR", header.data(), header.size());
  for (std::size_t at = 0; at < stream.size(); at += kIdatBytes) {
    putChunk(png, "IDAT", stream.data() + at, std::min(kIdatBytes, stream.size() - at));
  }
  putChunk(png, "IEND", nullptr, 0);
  return png;
}

}  // namespace

Decoded readPng(const std::filesystem::path& path) {
  const std::string name = path.string();
  PngContext ctx;
  ReadHandles h;
  h.file = std::fopen(name.c_str(), "rb");
  if (!h.file) throw makeError(name, ": cannot open: ", std::strerror(errno));
  std::setvbuf(h.file, nullptr, _IOFBF, 1 << 20);
  h.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, onPngError, onPngWarning);
  if (h.png) h.info = png_create_info_struct(h.png);
  if (!h.png || !h.info) throw makeError(name, ": out of memory starting the PNG reader");
  auto fail = [&](const char* stage) {
    // libpng's default reader says only "Read Error" when the file ends early.
    if (std::strcmp(ctx.message.data(), "Read Error") == 0) {
      return makeError(name, ": truncated PNG: the file ends inside the ", stage);
    }
    return makeError(name, ": cannot read PNG ", stage, " (truncated or corrupt?): ", ctx.message.data());
  };
  if (!startRead(h.png, h.info, h.file)) throw fail("header");
  const long long width = png_get_image_width(h.png, h.info);
  const long long height = png_get_image_height(h.png, h.info);
  if (width * height > kMaxImagePixels) checkPixelBudget(name, width, height, 1, 0, memoryBudget());
  // Deflate packs at most 1032 bytes into one: a header promising more than the file can
  // hold (a 74-byte file claiming 16384 x 16384 RGBA) is refused before anything is inflated.
  {
    const std::uintmax_t raw_row =
        (static_cast<std::uintmax_t>(width) * png_get_channels(h.png, h.info) * png_get_bit_depth(h.png, h.info) + 7) /
            8 +
        1;
    std::error_code ec;
    checkBodyCanHold(name, std::filesystem::file_size(path, ec), raw_row * height, 1032, "PNG");
  }
  int passes = 1;
  if (!configureRead(h.png, h.info, &passes)) throw fail("header");
  const int bits = png_get_bit_depth(h.png, h.info);
  const int channels = png_get_channels(h.png, h.info);
  if ((bits != 8 && bits != 16) || channels < 1 || channels > 4) {
    throw makeError(name, ": unsupported PNG layout (", bits, "-bit, ", channels, " channels)");
  }
  const std::size_t interlaced_buffer = passes == 1 ? 0 : png_get_rowbytes(h.png, h.info) * height;
  checkPixelBudget(name, width, height, channels, interlaced_buffer, memoryBudget());

  Decoded out;
  out.image = Image(static_cast<int>(width), static_cast<int>(height), channels);
  const std::size_t samples = static_cast<std::size_t>(width) * channels;
  const std::size_t row_bytes = png_get_rowbytes(h.png, h.info);
  SHANSHUI_CHECK_EQ(row_bytes, samples * (bits / 8));
  if (passes == 1) {
    // Row by row through a small buffer: memory stays at the float image.
    constexpr png_uint_32 kChunk = 32;
    std::vector<png_byte> buffer(row_bytes * kChunk);
    std::array<png_bytep, kChunk> rows{};
    for (png_uint_32 y = 0; y < height; y += kChunk) {
      const png_uint_32 n = std::min<png_uint_32>(kChunk, static_cast<png_uint_32>(height) - y);
      for (png_uint_32 i = 0; i < n; ++i) rows[i] = buffer.data() + i * row_bytes;
      if (!readRows(h.png, rows.data(), n)) throw fail("pixels");
      for (png_uint_32 i = 0; i < n; ++i) {
        convertRow(rows[i], &out.image.pixels[(y + i) * samples], samples, bits);
      }
    }
  } else {
    // Interlaced: the passes fill the whole image in turn.
    std::vector<png_byte> buffer(row_bytes * static_cast<std::size_t>(height));
    std::vector<png_bytep> rows(static_cast<std::size_t>(height));
    for (std::size_t y = 0; y < rows.size(); ++y) rows[y] = buffer.data() + y * row_bytes;
    if (!readImage(h.png, rows.data())) throw fail("pixels");
    for (std::size_t y = 0; y < rows.size(); ++y) convertRow(rows[y], &out.image.pixels[y * samples], samples, bits);
  }
  if (!finishRead(h.png)) throw fail("end");
  out.info.depth = bits == 16 ? PixelDepth::UInt16 : PixelDepth::UInt8;
  out.info.channels = channels;
  out.info.format = "png";
  return out;
}

std::string encodePng(const Image& img, const std::string& name, PixelDepth depth, bool smallest) {
  SHANSHUI_CHECK(depth == PixelDepth::UInt8 || depth == PixelDepth::UInt16);
  SHANSHUI_CHECK_GE(img.channels, 1);
  SHANSHUI_CHECK_LE(img.channels, 4);
  const int bits = depth == PixelDepth::UInt16 ? 16 : 8;
  if (!smallest) return encodePngParallel(img, name, bits);
  PngContext ctx;
  WriteHandles h;
  h.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, onPngError, onPngWarning);
  if (h.png) h.info = png_create_info_struct(h.png);
  if (!h.png || !h.info) throw makeError(name, ": out of memory starting the PNG writer");
  std::string bytes;
  const std::size_t samples = static_cast<std::size_t>(img.width) * img.channels;
  // Room for incompressible samples (deflate adds ~0.1 %), so the buffer never moves.
  bytes.reserve(samples * img.height * (bits / 8) * 1001 / 1000 + 4096);
  WriteSink sink{&bytes};
  auto fail = [&] { return makeError(name, ": cannot encode PNG: ", ctx.message.data()); };
  if (!startWrite(h.png, h.info, &sink, img, bits)) throw fail();
  std::vector<png_byte> row(samples * (bits / 8));
  for (int y = 0; y < img.height; ++y) {
    encodeRow(&img.pixels[static_cast<std::size_t>(y) * samples], samples, bits, row.data());
    if (!writeRow(h.png, row.data())) throw fail();
  }
  if (!finishWrite(h.png, h.info)) throw fail();
  return bytes;
}

}  // namespace shanshui::image::detail
