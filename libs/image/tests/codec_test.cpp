// The direct PNG, JPEG and PNM codecs (src/codecs.h) against OpenImageIO as the oracle:
// files written by one are read by the other to the same values, including the PNG
// layouts shanshui never writes (palette, 1-bit grey, tRNS, interlaced).
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <fstream>
#include <random>

#include <OpenImageIO/imageio.h>
#include <png.h>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "test_support.h"

namespace shanshui::image {
namespace {

// What OpenImageIO reads from `path`: float samples, straight alpha.
Image readWithOiio(const std::filesystem::path& path) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path.string(), &config);
  if (!in) throw std::runtime_error(OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  Image img(spec.width, spec.height, spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data())) {
    throw std::runtime_error(in->geterror());
  }
  return img;
}

void writeWithOiio(const Image& img, const std::filesystem::path& path, OIIO::TypeDesc type) {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(img.width, img.height, img.channels, type);
  if (img.hasAlpha()) {
    spec.alpha_channel = img.channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);
  }
  ASSERT_TRUE(out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, img.pixels.data()));
  ASSERT_TRUE(out->close());
}

Image randomCodes(int w, int h, int c, double levels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> code(0, static_cast<int>(levels));
  Image img(w, h, c);
  for (float& v : img.pixels) v = static_cast<float>(code(rng) / levels);
  return img;
}

// OpenImageIO turns code c into c * (1/255.f) and shanshui into float(c / 255.0): the same
// code can differ in the last bit; two codes differ by at least 1/65535.
constexpr float kSameCode = 1e-7f;

float maxAbsDiff(const Image& a, const Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  float d = 0;
  for (std::size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i) {
    d = std::max(d, std::abs(a.pixels[i] - b.pixels[i]));
  }
  return d;
}

// A PNG written with libpng itself in a layout given by colour type, bit depth and
// interlacing; the samples are random codes, palette entries random colours.
struct PngLayout {
  int colour_type;
  int bits;
  bool interlaced;
  bool transparency;  // a tRNS chunk
};

bool writeRawPng(std::FILE* file, const PngLayout& layout, int w, int h, std::vector<png_byte>& data) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, w, h, layout.bits, layout.colour_type,
               layout.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_color palette[16];
  png_byte alpha[16];
  for (int i = 0; i < 16; ++i) {
    palette[i] = {static_cast<png_byte>(i * 16), static_cast<png_byte>(255 - i * 9), static_cast<png_byte>(i * i)};
    alpha[i] = static_cast<png_byte>(i * 17);
  }
  if (layout.colour_type == PNG_COLOR_TYPE_PALETTE) png_set_PLTE(png, info, palette, 16);
  if (layout.transparency) {
    png_color_16 grey_key{};
    grey_key.gray = 1;
    if (layout.colour_type == PNG_COLOR_TYPE_PALETTE) {
      png_set_tRNS(png, info, alpha, 16, nullptr);
    } else {
      png_set_tRNS(png, info, nullptr, 0, &grey_key);
    }
  }
  png_write_info(png, info);
  const std::size_t row_bytes = png_get_rowbytes(png, info);
  data.resize(row_bytes * h);
  std::mt19937 rng(11);
  const int max_code = layout.colour_type == PNG_COLOR_TYPE_PALETTE ? 15 : (1 << layout.bits) - 1;
  // Packs random codes of `bits` bits into each row (one sample per pixel in these layouts).
  for (int y = 0; y < h; ++y) {
    png_byte* row = &data[y * row_bytes];
    std::fill(row, row + row_bytes, 0);
    for (int x = 0; x < w; ++x) {
      const int code = std::uniform_int_distribution<int>(0, max_code)(rng);
      if (layout.bits == 16) {
        row[2 * x] = static_cast<png_byte>(code >> 8);
        row[2 * x + 1] = static_cast<png_byte>(code);
      } else {
        const int bit = x * layout.bits;
        row[bit / 8] |= static_cast<png_byte>(code << (8 - layout.bits - bit % 8));
      }
    }
  }
  std::vector<png_bytep> rows(h);
  for (int y = 0; y < h; ++y) rows[y] = &data[y * row_bytes];
  png_write_image(png, rows.data());
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

TEST(Codecs, PngReaderAgreesWithOpenImageIOOnEveryLayout) {
  test::TempDir dir;
  const PngLayout layouts[] = {{PNG_COLOR_TYPE_GRAY, 1, false, false},  {PNG_COLOR_TYPE_GRAY, 2, true, false},
                               {PNG_COLOR_TYPE_GRAY, 4, false, true},   {PNG_COLOR_TYPE_GRAY, 8, true, false},
                               {PNG_COLOR_TYPE_GRAY, 16, true, false},  {PNG_COLOR_TYPE_PALETTE, 4, false, false},
                               {PNG_COLOR_TYPE_PALETTE, 8, true, true}, {PNG_COLOR_TYPE_PALETTE, 8, false, true}};
  int n = 0;
  for (const PngLayout& layout : layouts) {
    SCOPED_TRACE("colour type " + std::to_string(layout.colour_type) + ", " + std::to_string(layout.bits) + " bits" +
                 (layout.interlaced ? ", interlaced" : "") + (layout.transparency ? ", tRNS" : ""));
    const auto path = dir / ("layout" + std::to_string(n++) + ".png");
    std::vector<png_byte> data;
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    ASSERT_TRUE(writeRawPng(file, layout, 37, 29, data));
    std::fclose(file);
    ImageInfo info;
    const Image ours = loadImage(path, &info);
    const Image oracle = readWithOiio(path);
    ASSERT_EQ(ours.width, 37);
    ASSERT_EQ(ours.height, 29);
    ASSERT_EQ(ours.channels, oracle.channels);
    EXPECT_LE(maxAbsDiff(ours, oracle), kSameCode);
    EXPECT_EQ(info.format, "png");
  }
}

TEST(Codecs, PngWriterIsReadByOpenImageIOToTheSameCodes) {
  test::TempDir dir;
  for (const PixelDepth depth : {PixelDepth::UInt8, PixelDepth::UInt16}) {
    for (int channels = 1; channels <= 4; ++channels) {
      for (const bool smallest : {false, true}) {
        SCOPED_TRACE(std::string("depth ") + depthName(depth) + ", channels " + std::to_string(channels) +
                     (smallest ? ", smallest" : ""));
        const Image img = randomCodes(41, 19, channels, normalisationScale(depth), 3u + channels);
        const auto path = dir / "ours.png";
        saveImage(img, path, depth, {smallest});
        EXPECT_LE(maxAbsDiff(readWithOiio(path), img), kSameCode);
      }
    }
  }
}

// An image of many bands (the fast writer deflates ~1 MiB of rows per band, in parallel):
// the joined stream decodes to every code, and encoding twice gives the same bytes (the
// bands are joined in order, whichever thread finished first).
TEST(Codecs, ParallelPngWriterJoinsItsBandsIntoOneValidStream) {
  test::TempDir dir;
  for (const PixelDepth depth : {PixelDepth::UInt8, PixelDepth::UInt16}) {
    const Image img = randomCodes(731, 977, 3, normalisationScale(depth), 21);
    saveImage(img, dir / "bands.png", depth);
    EXPECT_LE(maxAbsDiff(readWithOiio(dir / "bands.png"), img), kSameCode) << depthName(depth);
    EXPECT_EQ(encodeImage(img, dir / "again.png", depth), encodeImage(img, dir / "again.png", depth));
    // A smooth ramp compresses (matches and Huffman codes, not stored blocks) in every band.
    const double levels = normalisationScale(depth);
    Image ramp(1500, 900, 1);
    for (int y = 0; y < ramp.height; ++y) {
      for (int x = 0; x < ramp.width; ++x) {
        ramp.at(x, y, 0) = static_cast<float>(std::floor(levels * (x + y) / (ramp.width + ramp.height)) / levels);
      }
    }
    const std::string bytes = encodeImage(ramp, dir / "ramp.png", depth);
    EXPECT_LT(bytes.size(), ramp.pixels.size() * (depth == PixelDepth::UInt16 ? 2 : 1) / 4) << depthName(depth);
    saveImage(ramp, dir / "ramp.png", depth);
    EXPECT_LE(maxAbsDiff(readWithOiio(dir / "ramp.png"), ramp), kSameCode) << depthName(depth);
  }
}

TEST(Codecs, PngsWrittenByOpenImageIOLoadExactly) {
  test::TempDir dir;
  for (const auto& [type, levels] :
       {std::pair{OIIO::TypeDesc::UINT8, 255.0}, std::pair{OIIO::TypeDesc::UINT16, 65535.0}}) {
    for (int channels = 1; channels <= 4; ++channels) {
      const Image img = randomCodes(23, 31, channels, levels, 9u + channels);
      const auto path = dir / "theirs.png";
      writeWithOiio(img, path, type);
      EXPECT_LE(maxAbsDiff(loadImage(path), img), kSameCode) << channels << " channels, " << levels;
    }
  }
}

TEST(Codecs, JpegDecodesAsOpenImageIODoesBothWays) {
  test::TempDir dir;
  for (int channels : {1, 3}) {
    const Image img = randomCodes(64, 40, channels, 255.0, 5u + channels);
    saveImage(img, dir / "ours.jpg");
    EXPECT_LE(maxAbsDiff(loadImage(dir / "ours.jpg"), readWithOiio(dir / "ours.jpg")), 1.0f / 255) << channels;
    writeWithOiio(img, dir / "theirs.jpg", OIIO::TypeDesc::UINT8);
    EXPECT_LE(maxAbsDiff(loadImage(dir / "theirs.jpg"), readWithOiio(dir / "theirs.jpg")), 1.0f / 255) << channels;
  }
}

// A complete JPEG followed by more than the 4 KB the earlier end-marker check looked at
// (camera files carry such trailers) is accepted; the same file cut short is not.
TEST(Codecs, JpegWithLongTrailerIsCompleteButCutJpegIsNot) {
  test::TempDir dir;
  saveImage(randomCodes(80, 60, 3, 255.0, 2), dir / "a.jpg");
  std::ifstream in(dir / "a.jpg", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "trailer.jpg", std::ios::binary) << bytes << std::string(10000, 'x');
  EXPECT_EQ(maxAbsDiff(loadImage(dir / "trailer.jpg"), loadImage(dir / "a.jpg")), 0.0f);
  std::ofstream(dir / "cut.jpg", std::ios::binary) << bytes.substr(0, bytes.size() - 200);
  test::expectErrorNaming([&] { loadImage(dir / "cut.jpg"); }, "cut.jpg", "truncated JPEG");
}

TEST(Codecs, EightBitPnmMatchesOpenImageIOBothWays) {
  test::TempDir dir;
  for (const char* ext : {".pgm", ".ppm"}) {
    const int channels = std::string(ext) == ".pgm" ? 1 : 3;
    const Image img = randomCodes(17, 13, channels, 255.0, 4);
    saveImage(img, dir / (std::string("ours") + ext));
    EXPECT_LE(maxAbsDiff(readWithOiio(dir / (std::string("ours") + ext)), img), kSameCode) << ext;
    writeWithOiio(img, dir / (std::string("theirs") + ext), OIIO::TypeDesc::UINT8);
    EXPECT_LE(maxAbsDiff(loadImage(dir / (std::string("theirs") + ext)), img), kSameCode) << ext;
  }
}

// Formats behind the module arrive through it; its errors name the file like the others.
TEST(Codecs, ModuleFormatsLoadAndReportErrorsByName) {
  test::TempDir dir;
  const Image img = randomCodes(9, 7, 3, 255.0, 8);
  saveImage(img, dir / "a.tif");
  ImageInfo info;
  EXPECT_LE(maxAbsDiff(loadImage(dir / "a.tif", &info), img), kSameCode);
  EXPECT_EQ(info.format, "tiff");
  std::ofstream(dir / "bad.tif", std::ios::binary) << "II*\0garbage";
  test::expectErrorNaming([&] { loadImage(dir / "bad.tif"); }, "bad.tif", "cannot read");
}

}  // namespace
}  // namespace shanshui::image
