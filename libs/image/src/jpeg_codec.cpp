// JPEG with libjpeg (libjpeg-turbo). As for PNG, errors arrive by longjmp: each call that
// can fail runs in a small function of its own holding the setjmp.
#include <algorithm>
#include <array>
#include <cerrno>
#include <csetjmp>
#include <cstdio>  // before jpeglib.h, which uses FILE
#include <cstdlib>
#include <cstring>
#include <vector>

#include <jerror.h>
#include <jpeglib.h>

#include "codecs.h"
#include "shanshui/core/error.h"

namespace shanshui::image::detail {
namespace {

struct JpegErrors {
  jpeg_error_mgr mgr{};
  std::jmp_buf jump{};
  std::array<char, JMSG_LENGTH_MAX> message{};
  bool truncated = false;
};

void onJpegError(j_common_ptr cinfo) {
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, errors->message.data());
  std::longjmp(errors->jump, 1);
}

// libjpeg decodes a cut file to its end, filling the missing rows with grey and only
// warning "Premature end of JPEG file"; that warning is an error here. Other warnings
// (extraneous bytes before a marker, common in camera files) are dropped: they would be a
// second line on stderr and do not lose pixels.
void onJpegMessage(j_common_ptr cinfo, int level) {
  auto* errors = reinterpret_cast<JpegErrors*>(cinfo->err);
  if (level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF) errors->truncated = true;
}

jpeg_error_mgr* installErrors(JpegErrors& errors) {
  jpeg_std_error(&errors.mgr);
  errors.mgr.error_exit = onJpegError;
  errors.mgr.emit_message = onJpegMessage;
  return &errors.mgr;
}

struct Decompress {
  jpeg_decompress_struct cinfo{};
  JpegErrors errors;
  std::FILE* file = nullptr;
  bool created = false;
  ~Decompress() {
    if (created) jpeg_destroy_decompress(&cinfo);
    if (file) std::fclose(file);
  }
};

bool readHeader(Decompress& d) {
  if (setjmp(d.errors.jump)) return false;
  jpeg_create_decompress(&d.cinfo);
  d.created = true;
  jpeg_stdio_src(&d.cinfo, d.file);
  jpeg_read_header(&d.cinfo, TRUE);
  return true;
}

bool startDecompress(Decompress& d, bool grey) {
  if (setjmp(d.errors.jump)) return false;
  d.cinfo.out_color_space = grey ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_start_decompress(&d.cinfo);
  return true;
}

bool readScanlines(Decompress& d, JSAMPARRAY rows, JDIMENSION count) {
  if (setjmp(d.errors.jump)) return false;
  JDIMENSION done = 0;
  while (done < count) done += jpeg_read_scanlines(&d.cinfo, rows + done, count - done);
  return true;
}

bool finishDecompress(Decompress& d) {
  if (setjmp(d.errors.jump)) return false;
  jpeg_finish_decompress(&d.cinfo);
  return true;
}

struct Compress {
  jpeg_compress_struct cinfo{};
  JpegErrors errors;
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  bool created = false;
  ~Compress() {
    if (created) jpeg_destroy_compress(&cinfo);
    std::free(buffer);
  }
};

bool startCompress(Compress& c, const Image& img, int quality) {
  if (setjmp(c.errors.jump)) return false;
  jpeg_create_compress(&c.cinfo);
  c.created = true;
  jpeg_mem_dest(&c.cinfo, &c.buffer, &c.size);
  c.cinfo.image_width = static_cast<JDIMENSION>(img.width);
  c.cinfo.image_height = static_cast<JDIMENSION>(img.height);
  c.cinfo.input_components = img.channels;
  c.cinfo.in_color_space = img.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&c.cinfo);
  jpeg_set_quality(&c.cinfo, quality, TRUE);
  jpeg_start_compress(&c.cinfo, TRUE);
  return true;
}

bool writeScanline(Compress& c, JSAMPROW row) {
  if (setjmp(c.errors.jump)) return false;
  jpeg_write_scanlines(&c.cinfo, &row, 1);
  return true;
}

bool finishCompress(Compress& c) {
  if (setjmp(c.errors.jump)) return false;
  jpeg_finish_compress(&c.cinfo);
  return true;
}

}  // namespace

Decoded readJpeg(const std::filesystem::path& path) {
  const std::string name = path.string();
  Decompress d;
  d.cinfo.err = installErrors(d.errors);
  d.file = std::fopen(name.c_str(), "rb");
  if (!d.file) throw makeError(name, ": cannot open: ", std::strerror(errno));
  auto fail = [&](const char* stage) {
    return makeError(name, ": cannot read JPEG ", stage, " (truncated or corrupt?): ", d.errors.message.data());
  };
  if (!readHeader(d)) throw fail("header");
  checkPixelBudget(name, d.cinfo.image_width, d.cinfo.image_height, d.cinfo.num_components == 1 ? 1 : 3, 0,
                   memoryBudget());
  const int components = d.cinfo.num_components;
  if (d.cinfo.jpeg_color_space == JCS_CMYK || d.cinfo.jpeg_color_space == JCS_YCCK) {
    Decoded out;  // libjpeg cannot convert CMYK to RGB; OpenImageIO can
    const std::string error = oiioCodec(name, "reading a CMYK JPEG").load(name, "jpeg", memoryBudget(), &out);
    if (!error.empty()) throw Error(error);
    return out;
  }
  const bool grey = components == 1;
  if (!startDecompress(d, grey)) throw fail("header");
  const int channels = grey ? 1 : 3;
  SHANSHUI_CHECK_EQ(d.cinfo.output_components, channels);

  Decoded out;
  out.image = Image(static_cast<int>(d.cinfo.output_width), static_cast<int>(d.cinfo.output_height), channels);
  const std::size_t samples = static_cast<std::size_t>(out.image.width) * channels;
  constexpr JDIMENSION kChunk = 16;
  std::vector<JSAMPLE> buffer(samples * kChunk);
  std::array<JSAMPROW, kChunk> rows{};
  std::array<float, 256> table{};
  for (int c = 0; c < 256; ++c) table[c] = static_cast<float>(c / 255.0);
  const auto height = static_cast<JDIMENSION>(out.image.height);
  for (JDIMENSION y = 0; y < height; y += kChunk) {
    const JDIMENSION n = std::min(kChunk, height - y);
    for (JDIMENSION i = 0; i < n; ++i) rows[i] = buffer.data() + i * samples;
    if (!readScanlines(d, rows.data(), n)) throw fail("pixels");
    float* dst = &out.image.pixels[static_cast<std::size_t>(y) * samples];
    for (std::size_t i = 0; i < n * samples; ++i) dst[i] = table[buffer[i]];
  }
  if (d.errors.truncated) throw makeError(name, ": truncated JPEG (premature end of file)");
  if (!finishDecompress(d)) throw fail("end");
  if (d.errors.truncated) throw makeError(name, ": truncated JPEG (premature end of file)");
  out.info.depth = PixelDepth::UInt8;
  out.info.channels = channels;
  out.info.format = "jpeg";
  return out;
}

std::string encodeJpeg(const Image& img, const std::string& name) {
  SHANSHUI_CHECK(img.channels == 1 || img.channels == 3);
  Compress c;
  c.cinfo.err = installErrors(c.errors);
  auto fail = [&] { return makeError(name, ": cannot encode JPEG: ", c.errors.message.data()); };
  // Quality 95 with libjpeg's default 4:2:0 chroma: visually lossless for ink renders.
  if (!startCompress(c, img, 95)) throw fail();
  const std::size_t samples = static_cast<std::size_t>(img.width) * img.channels;
  std::vector<JSAMPLE> row(samples);
  for (int y = 0; y < img.height; ++y) {
    const float* src = &img.pixels[static_cast<std::size_t>(y) * samples];
    for (std::size_t i = 0; i < samples; ++i) row[i] = static_cast<JSAMPLE>(sampleCode(src[i], 255));
    if (!writeScanline(c, row.data())) throw fail();
  }
  if (!finishCompress(c)) throw fail();
  return std::string(reinterpret_cast<const char*>(c.buffer), c.size);
}

}  // namespace shanshui::image::detail
