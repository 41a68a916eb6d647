#include <fstream>
#include <random>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/image/convert.h"
#include "shanshui/image/image_io.h"
#include "shanshui/image/opencv_interop.h"
#include "test_support.h"

namespace shanshui::image {
namespace {

// Random pixels that the depth can store exactly: k / (2^bits - 1).
Image randomImage(int w, int h, int c, PixelDepth depth, unsigned seed) {
  std::mt19937 rng(seed);
  Image img(w, h, c);
  const double levels = normalisationScale(depth);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (float& v : img.pixels) {
    v = u(rng);
    if (levels > 1.0) v = static_cast<float>(std::round(v * levels) / levels);
  }
  return img;
}

float maxAbsDiff(const Image& a, const Image& b) {
  float d = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) d = std::max(d, std::abs(a.pixels[i] - b.pixels[i]));
  return d;
}

struct RoundTrip {
  const char* ext;
  PixelDepth depth;
};

TEST(ImageIo, RoundTripsEveryFormatDepthAndChannelCount) {
  test::TempDir dir;
  const RoundTrip cases[] = {{".png", PixelDepth::UInt8},  {".png", PixelDepth::UInt16}, {".tif", PixelDepth::UInt8},
                             {".tif", PixelDepth::UInt16}, {".tif", PixelDepth::Float},  {".exr", PixelDepth::Float}};
  for (const RoundTrip& rt : cases) {
    for (int channels = 1; channels <= 4; ++channels) {
      SCOPED_TRACE(std::string(rt.ext) + " depth " + depthName(rt.depth) + " channels " + std::to_string(channels));
      const Image img = randomImage(37, 23, channels, rt.depth, 7u + channels);
      const auto path = dir / ("img" + std::to_string(channels) + rt.ext);
      saveImage(img, path, rt.depth);
      ImageInfo info;
      const Image back = loadImage(path, &info);
      ASSERT_EQ(back.width, img.width);
      ASSERT_EQ(back.height, img.height);
      ASSERT_EQ(back.channels, img.channels);
      EXPECT_EQ(info.depth, rt.depth);
      const double levels = normalisationScale(rt.depth);
      if (levels > 1.0) {  // integer files: the stored values are exactly the same
        for (std::size_t i = 0; i < img.pixels.size(); ++i) {
          ASSERT_EQ(std::lround(img.pixels[i] * levels), std::lround(back.pixels[i] * levels)) << i;
        }
        EXPECT_LE(maxAbsDiff(img, back), 1e-6f);
      } else if (std::string(rt.ext) == ".exr" && img.hasAlpha()) {
        EXPECT_LE(maxAbsDiff(img, back), 1e-6f);  // premultiplied on disk: c·a/a rounds
      } else {
        EXPECT_EQ(maxAbsDiff(img, back), 0.0f);
      }
    }
  }
}

TEST(ImageIo, JpegIsLossyButClose) {
  test::TempDir dir;
  // A smooth ramp: JPEG keeps it within a few levels.
  for (int channels : {1, 3}) {
    Image img(64, 48, channels);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < channels; ++c) img.at(x, y, c) = (x + 2 * y + 10 * c) / 200.0f;
    saveImage(img, dir / "ramp.jpg");
    const Image back = loadImage(dir / "ramp.jpg");
    EXPECT_EQ(back.channels, channels);
    EXPECT_LT(maxAbsDiff(img, back), 0.03f);
  }
  EXPECT_THROW(saveImage(Image(4, 4, 4, 0.5f), dir / "alpha.jpg"), Error);
}

TEST(ImageIo, ReadsGif) {
  test::TempDir dir;
  // OpenImageIO writes GIF with a palette: grey levels that a palette holds exactly.
  Image img(16, 8, 3);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>((x / 4) * 85) / 255.0f;
  const auto path = dir / "steps.gif";
  try {
    saveImage(img, path);
  } catch (const Error& e) {
    GTEST_SKIP() << "this OpenImageIO cannot write GIF to make the input: " << e.what();
  }
  const Image back = loadImage(path);
  ASSERT_EQ(back.width, 16);
  const Image grey = toGrey(back);
  for (int x = 0; x < 16; ++x) EXPECT_NEAR(grey.at(x, 3), (x / 4) * 85 / 255.0f, 1.5f / 255) << x;
}

TEST(ImageIo, StraightAlphaSurvivesPng) {
  // A fully transparent pixel keeps its colour: nothing premultiplies on the way.
  test::TempDir dir;
  Image img(2, 1, 4);
  img.pixels = {1.0f, 0.0f, 0.0f, 0.0f, 0.2f, 0.4f, 0.6f, 0.4f};
  saveImage(img, dir / "a.png");
  const Image back = loadImage(dir / "a.png");
  EXPECT_LE(maxAbsDiff(img, back), 0.5f / 255);
}

TEST(ImageIo, BadInputNamesTheFile) {
  test::TempDir dir;
  auto expectError = [](const std::filesystem::path& p, const char* what) {
    test::expectErrorNaming([&] { loadImage(p); }, p.string(), what);
  };
  expectError(dir / "missing.png", "no such file");
  std::ofstream(dir / "empty.png").close();
  expectError(dir / "empty.png", "empty file");
  std::ofstream(dir / "text.png") << "this is not a png";
  expectError(dir / "text.png", "cannot read");
  // A real PNG cut in half.
  saveImage(randomImage(256, 256, 3, PixelDepth::UInt8, 3), dir / "full.png");
  std::ifstream in(dir / "full.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "cut.png", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  EXPECT_THROW(loadImage(dir / "cut.png"), Error);
}

// The reader is chosen once, by the first bytes or else by the extension; no other reader
// is tried on a file its own refused (OpenImageIO would try each one it has).
TEST(ImageIo, TheFirstBytesOrTheExtensionChooseOneReader) {
  test::TempDir dir;
  const Image img = randomImage(19, 11, 3, PixelDepth::UInt16, 5);
  for (const char* ext : {".tif", ".exr", ".png"}) {
    SCOPED_TRACE(ext);
    const auto real = dir / (std::string("real") + ext);
    saveImage(img, real, ext == std::string(".exr") ? PixelDepth::Float : PixelDepth::UInt16);
    const auto misnamed = dir / (std::string("scan_") + (ext + 1) + ".dat");  // no reader goes by .dat
    std::filesystem::copy_file(real, misnamed);
    ImageInfo info;
    const Image back = loadImage(misnamed, &info);
    EXPECT_EQ(back.width, img.width);
    EXPECT_LE(maxAbsDiff(img, back), 1e-3f);
  }
  // A TIFF named .png is read by its bytes, not refused by the PNG reader.
  std::filesystem::copy_file(dir / "real.tif", dir / "tiff_inside.png");
  EXPECT_EQ(loadImage(dir / "tiff_inside.png").width, img.width);
  // Bytes no reader signs, under an extension with no reader: refused by name, and what
  // says why is the extension's reader (none), not the last of a dozen that were tried.
  std::ofstream(dir / "noise.dat") << std::string(4096, '\x5a');
  test::expectErrorNaming([&] { loadImage(dir / "noise.dat"); }, "noise.dat", "cannot read image");
  // A large file of zeros under an extension whose reader refuses it: the refusal costs a
  // header's read. (OpenImageIO on its own went on to every reader, one of which read it
  // all: 98 s and 900 MB for 800 MB of zeros.) The bytes this process reads, from
  // /proc/self/io, are the oracle.
  auto bytesRead = [] {
    std::ifstream io("/proc/self/io");
    std::string key;
    long long value = 0;
    while (io >> key >> value)
      if (key == "rchar:") return value;
    return -1LL;
  };
  for (const char* name : {"zeros.tga", "zeros.png"}) {
    SCOPED_TRACE(name);
    {
      std::ofstream zeros(dir / name, std::ios::binary);
      const std::string block(1 << 20, '\0');
      for (int i = 0; i < 48; ++i) zeros << block;
    }
    const long long before = bytesRead();
    if (before < 0) GTEST_SKIP() << "no /proc/self/io to count the bytes read";
    EXPECT_THROW(loadImage(dir / name), Error);
    EXPECT_LT(bytesRead() - before, 4 << 20) << "of a 48 MiB file";
  }
  // A TIFF signature on something that is not a TIFF: the TIFF reader says so.
  std::ofstream(dir / "fake.tif") << "II*" << '\0' << std::string(64, '\x01');
  test::expectErrorNaming([&] { loadImage(dir / "fake.tif"); }, "fake.tif", "tiff");
}

TEST(ImageIo, FailedSaveKeepsTheExistingFile) {
  test::TempDir dir;
  const auto path = dir / "keep.png";
  const Image good = randomImage(8, 8, 1, PixelDepth::UInt8, 1);
  saveImage(good, path);
  Image bad = good;
  bad.pixels[5] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(saveImage(bad, path), Error);
  EXPECT_THROW(saveImage(Image(), path), Error);
  EXPECT_THROW(saveImage(good, dir / "x.unknownext"), Error);
  EXPECT_LE(maxAbsDiff(loadImage(path), good), 1e-6f);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
}

// 16-bit PGM: the codes on disk are the ones asked for (parsed here independently of
// OpenImageIO), and the file loads to the same values as the same data in a 16-bit PNG.
TEST(ImageIo, SixteenBitPgmKeepsEveryCode) {
  test::TempDir dir;
  Image img = randomImage(61, 17, 1, PixelDepth::UInt16, 5);
  img.pixels[0] = 1.0f;  // the top code, which OpenImageIO 2.4 reads one lower
  img.pixels[1] = 0.0f;
  saveImage(img, dir / "a.pgm", PixelDepth::UInt16);
  saveImage(img, dir / "a.png", PixelDepth::UInt16);
  std::ifstream in(dir / "a.pgm", std::ios::binary);
  std::string magic;
  int w = 0, h = 0, maxval = 0;
  in >> magic >> w >> h >> maxval;
  in.get();
  ASSERT_EQ(magic, "P5");
  ASSERT_EQ(maxval, 65535);
  ASSERT_EQ(w * h, static_cast<int>(img.pixels.size()));
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const int hi = in.get(), lo = in.get();
    ASSERT_EQ(hi << 8 | lo, std::lround(img.pixels[i] * 65535.0)) << i;
  }
  ImageInfo info;
  const Image pgm = loadImage(dir / "a.pgm", &info), png = loadImage(dir / "a.png");
  EXPECT_EQ(info.depth, PixelDepth::UInt16);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    ASSERT_EQ(std::lround(pgm.pixels[i] * 65535.0), std::lround(png.pixels[i] * 65535.0)) << i;
  }
}

TEST(ImageIo, DepthTheFormatCannotStoreIsRefusedNotNarrowed) {
  test::TempDir dir;
  const Image img = randomImage(8, 8, 1, PixelDepth::UInt16, 2);
  test::expectErrorNaming([&] { saveImage(img, dir / "a.jpg", PixelDepth::UInt16); }, "a.jpg", "cannot store 16-bit");
  test::expectErrorNaming([&] { saveImage(img, dir / "a.png", PixelDepth::Float); }, "a.png", "cannot store float");
  EXPECT_EQ(closestDepth(dir / "a.jpg", PixelDepth::UInt16), PixelDepth::UInt8);
  EXPECT_EQ(closestDepth(dir / "a.png", PixelDepth::Float), PixelDepth::UInt16);
  EXPECT_EQ(closestDepth(dir / "a.tif", PixelDepth::Float), PixelDepth::Float);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(ImageIo, HugeHeaderAndCutJpegAreRefusedByName) {
  test::TempDir dir;
  // A PNG header that claims 100000 x 100000 pixels, with almost no data behind it.
  const unsigned char png[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
                               0x44, 0x52, 0x00, 0x01, 0x86, 0xa0, 0x00, 0x01, 0x86, 0xa0, 0x08, 0x00, 0x00, 0x00,
                               0x00, 0x8d, 0x39, 0x54, 0x14, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x78,
                               0x9c, 0x63, 0x60, 0xa0, 0x3d, 0x00, 0x00, 0x00, 0x64, 0x00, 0x01, 0x86, 0x64, 0x3c,
                               0x35, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  std::ofstream(dir / "huge.png", std::ios::binary).write(reinterpret_cast<const char*>(png), sizeof png);
  test::expectErrorNaming([&] { loadImage(dir / "huge.png"); }, "huge.png", "more than the limit");
  saveImage(randomImage(96, 64, 3, PixelDepth::UInt8, 4), dir / "full.jpg");
  std::ifstream in(dir / "full.jpg", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir / "half.jpg", std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  EXPECT_NO_THROW(loadImage(dir / "full.jpg"));
  test::expectErrorNaming([&] { loadImage(dir / "half.jpg"); }, "half.jpg", "truncated JPEG");
}

// A grey 8-bit TIFF with its directory first and one strip of pixel data after it (as
// GDAL and many scanners write them), of which only `keep` bytes of the strip are there.
std::string stripTiff(int w, int h, std::size_t keep) {
  std::string t("II*\0", 4);
  auto u16 = [&](unsigned v) { t.push_back(static_cast<char>(v & 0xff)), t.push_back(static_cast<char>(v >> 8)); };
  auto u32 = [&](unsigned v) { u16(v & 0xffff), u16(v >> 16); };
  u32(8);  // the directory right after the header
  const unsigned entries = 9, data = 8 + 2 + entries * 12 + 4;
  u16(entries);
  auto entry = [&](unsigned tag, unsigned type, unsigned value) {
    u16(tag), u16(type), u32(1), type == 3 ? (u16(value), u16(0)) : u32(value);
  };
  entry(256, 3, w), entry(257, 3, h), entry(258, 3, 8), entry(259, 3, 1), entry(262, 3, 1);
  entry(273, 4, data), entry(277, 3, 1), entry(278, 3, h), entry(279, 4, static_cast<unsigned>(w * h));
  u32(0);  // no next directory
  for (int i = 0; i < w * h && static_cast<std::size_t>(i) < keep; ++i) t.push_back(static_cast<char>(i * 7));
  return t;
}

TEST(ImageIo, ACutTiffIsRefusedNotReadAsBlackRows) {
  test::TempDir dir;
  const std::string whole = stripTiff(40, 30, 40 * 30), cut = stripTiff(40, 30, 40 * 12);
  std::ofstream(dir / "whole.tif", std::ios::binary).write(whole.data(), static_cast<std::streamsize>(whole.size()));
  std::ofstream(dir / "cut.tif", std::ios::binary).write(cut.data(), static_cast<std::streamsize>(cut.size()));
  const Image img = loadImage(dir / "whole.tif");
  EXPECT_EQ(img.width, 40);
  EXPECT_NEAR(img.at(3, 0, 0), (3 * 7 % 256) / 255.0f, 1e-6f) << "the hand-made TIFF reads as written";
  test::expectErrorNaming([&] { loadImage(dir / "cut.tif"); }, "cut.tif", "truncated or corrupt");
}

// A PNG chunk: length, type, data and the CRC-32 libpng checks on every critical chunk.
std::string pngChunk(const std::string& type, const std::string& data) {
  auto be32 = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                       static_cast<char>(v)};
  };
  std::uint32_t crc = 0xffffffffu;
  for (unsigned char c : type + data) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(~crc);
}

TEST(ImageIo, AHeaderPromisingMoreThanTheFileCanHoldIsRefusedBeforeDecoding) {
  test::TempDir dir;
  // The outside test's case: 16384 x 16384 16-bit RGBA (4 GiB as floats) in 74 bytes.
  const std::string ihdr{0, 0, 0x40, 0, 0, 0, 0x40, 0, 16, 6, 0, 0, 0};
  const std::string idat{0x78, static_cast<char>(0x9c), 0x63, 0x60, 0, 0, 0, 2, 0, 1};
  const std::string png =
      std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) + pngChunk("IDAT", idat) + pngChunk("IEND", "");
  ASSERT_LT(png.size(), 80u);
  std::ofstream(dir / "claims.png", std::ios::binary).write(png.data(), static_cast<std::streamsize>(png.size()));
  test::expectErrorNaming([&] { loadImage(dir / "claims.png"); }, "claims.png", "truncated or corrupt PNG");
  // An uncompressed PNM must hold every sample.
  std::ofstream(dir / "short.ppm", std::ios::binary) << "P6\n4000 3000\n255\n" << std::string(100, 'x');
  test::expectErrorNaming([&] { loadImage(dir / "short.ppm"); }, "short.ppm", "truncated or corrupt PNM");
  // So must ASCII and bitmap PNM, which OpenImageIO decodes: the fuzzer's 14-byte P4 of
  // 99949994 x 1 and 23-byte P2 of 77777777 x 1 made it allocate half a gigabyte. Whole
  // small ones of each kind still read.
  std::ofstream(dir / "wide.pbm", std::ios::binary) << "P499949994 1\n6";
  std::ofstream(dir / "wide.pgm", std::ios::binary) << "P2#\n77777777\n\n\n1\n\n62\n\n\n";
  test::expectErrorNaming([&] { loadImage(dir / "wide.pbm"); }, "wide.pbm", "truncated or corrupt PNM");
  test::expectErrorNaming([&] { loadImage(dir / "wide.pgm"); }, "wide.pgm", "truncated or corrupt PNM");
  // Sides whose product overflows 64 bits (the fuzzer's 6666966665 x 3666966665 P6).
  std::ofstream(dir / "huge.ppm", std::ios::binary) << "P6666966665\n3666966665\n3\n6";
  test::expectErrorNaming([&] { loadImage(dir / "huge.ppm"); }, "huge.ppm", "expected sides under 2147483648");
  std::ofstream(dir / "ok.pbm", std::ios::binary) << "P4\n9 2\n" << std::string("\xff\x80\x00\x00", 4);
  std::ofstream(dir / "ok.pgm", std::ios::binary) << "P2\n3 1\n9\n0 4 9\n";
  std::ofstream(dir / "ok.ppm", std::ios::binary) << "P3 1 1 255 10 20 30";
  std::ofstream(dir / "ok1.pbm", std::ios::binary) << "P1\n3 1\n0 1 0\n";
  EXPECT_EQ(loadImage(dir / "ok.pbm").width, 9);
  EXPECT_NEAR(loadImage(dir / "ok.pgm").at(1, 0, 0), 4.0 / 9.0, 0.5 / 255);  // OpenImageIO goes through 8 bits
  EXPECT_EQ(loadImage(dir / "ok.ppm").channels, 3);
  EXPECT_EQ(loadImage(dir / "ok1.pbm").width, 3);
  // The same layout, whole, still reads: the bound is the format's, not a guess.
  const Image small = randomImage(64, 48, 4, PixelDepth::UInt16, 5);
  saveImage(small, dir / "whole.png", PixelDepth::UInt16);
  EXPECT_EQ(loadImage(dir / "whole.png").width, 64);
}

TEST(ImageIo, TheMemoryBudgetRefusesAnImageByItsHeader) {
  test::TempDir dir;
  const Image img = randomImage(256, 128, 3, PixelDepth::UInt8, 6);
  const std::uintmax_t need = 256 * 128 * 3 * sizeof(float);
  for (const char* name : {"a.png", "a.jpg", "a.ppm", "a.tif"}) {
    saveImage(img, dir / name);
    setMemoryBudget(need * 2);  // room for a decoder's own buffer
    EXPECT_EQ(loadImage(dir / name).height, 128) << name;
    setMemoryBudget(need / 2);
    test::expectErrorNaming([&] { loadImage(dir / name); }, name, "more than the memory budget");
  }
  setMemoryBudget(0);
  EXPECT_GT(memoryBudget(), need) << "the default budget is restored";
}

TEST(Convert, GreyUsesStatedLumaWeightsAfterCompositingOverWhite) {
  Image rgb(3, 1, 3, 0.0f);
  rgb.at(0, 0, 0) = 1;
  rgb.at(1, 0, 1) = 1;
  rgb.at(2, 0, 2) = 1;
  const Image g = toGrey(rgb);
  EXPECT_FLOAT_EQ(g.at(0, 0), 0.299f);
  EXPECT_FLOAT_EQ(g.at(1, 0), 0.587f);
  EXPECT_FLOAT_EQ(g.at(2, 0), 0.114f);
  // Black at half coverage over white is mid grey; transparent anything is white.
  Image rgba(2, 1, 4, 0.0f);
  rgba.at(0, 0, 3) = 0.5f;
  rgba.at(1, 0, 0) = 0.3f;
  const Image g2 = toGrey(rgba);
  EXPECT_FLOAT_EQ(g2.at(0, 0), 0.5f);
  EXPECT_FLOAT_EQ(g2.at(1, 0), 1.0f);
  // Agrees with OpenImageIO's own channel sum on an opaque random image.
  const Image r = randomImage(19, 7, 3, PixelDepth::Float, 11);
  OIIO::ImageBuf src(OIIO::ImageSpec(r.width, r.height, 3, OIIO::TypeDesc::FLOAT), const_cast<float*>(r.pixels.data()));
  const float w[3] = {kLumaR, kLumaG, kLumaB};
  OIIO::ImageBuf sum = OIIO::ImageBufAlgo::channel_sum(src, w);
  const Image mine = toGrey(r);
  for (int y = 0; y < r.height; ++y)
    for (int x = 0; x < r.width; ++x) EXPECT_NEAR(mine.at(x, y), sum.getchannel(x, y, 0, 0), 1e-6);
}

TEST(OpenCvInterop, MatViewsShareMemory) {
  Image img(5, 4, 3, 0.25f);
  cv::Mat m = asMat(img);
  EXPECT_EQ(m.data, reinterpret_cast<uchar*>(img.pixels.data()));
  EXPECT_EQ(m.type(), CV_32FC3);
  m.at<cv::Vec3f>(2, 1)[2] = 0.75f;  // row 2, column 1
  EXPECT_FLOAT_EQ(img.at(1, 2, 2), 0.75f);
  cv::Mat u16(3, 2, CV_16UC1, cv::Scalar(65535));
  u16.at<uint16_t>(1, 1) = 0;
  const Image back = imageFromMat(u16);
  EXPECT_EQ(back.width, 2);
  EXPECT_EQ(back.height, 3);
  EXPECT_FLOAT_EQ(back.at(0, 0), 1.0f);
  EXPECT_FLOAT_EQ(back.at(1, 1), 0.0f);
}

}  // namespace
}  // namespace shanshui::image
