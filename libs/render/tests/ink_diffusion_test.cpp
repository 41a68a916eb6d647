// The GPU ink diffusion against the CPU reference (libs/ink) on the grid of extreme
// parameters of SPEC.md section 9, and its own invariants.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "gl_test.h"
#include "shanshui/ink/diffusion.h"
#include "shanshui/render/ink_diffusion_pass.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

// Some tests choose the pass's layout through SHANSHUI_PIXEL_PASSES; it never outlives one,
// even one that stops at a failed assertion.
class InkGpu : public test::HeadlessGl {
 protected:
  void TearDown() override {
    unsetenv("SHANSHUI_PIXEL_PASSES");
    test::HeadlessGl::TearDown();
  }
};

const double kPaper[3] = {0.95, 0.93, 0.87};

// A picture on paper with strokes of several greys (values exact in 8 bits), optionally
// with strokes along the left, right and bottom borders.
image::Image picture(int w, int h, unsigned seed, bool border) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 99), grey(0, 120);
  image::Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int r = u(rng);
      const bool stroke = r < 6 || (border && (x == 0 || x == w - 1 || y == h - 1));
      const double t = stroke ? grey(rng) / 255.0 : (r < 15 ? 0.7 + 0.2 * (r % 3) : 1.0);
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = std::round(static_cast<float>(kPaper[c] * t) * 255.0f) / 255.0f;
    }
  return img;
}

image::Image absorbencyImage(int w, int h, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 255);
  image::Image a(w, h, 1);
  for (float& v : a.pixels) v = static_cast<float>(u(rng)) / 255.0f;
  return a;
}

// Both layouts: llvmpipe's (boundary invocations of 8 columns, the main region swept by rows
// and columns) and a GPU's (invocations of 2 columns, the main region gathered for d ≤ 8),
// forced on llvmpipe by SHANSHUI_PIXEL_PASSES.
TEST_F(InkGpu, MatchesTheCpuReferenceOnTheExtremeGrid) {
  for (const char* layout : {"fragment", "compute"}) {
    SCOPED_TRACE(layout);
    setenv("SHANSHUI_PIXEL_PASSES", layout, 1);
    InkDiffusionPass pass;
    unsetenv("SHANSHUI_PIXEL_PASSES");
    const glm::vec3 paper(kPaper[0], kPaper[1], kPaper[2]);
    double worst_max = 0, worst_mean = 0;
    int cases = 0;
    // The pass packs two pixels to a texel, its boundary invocations own 8 columns each and
    // walk strips of rows: widths 48, 47 and 45 end on a whole invocation, in a half-empty
    // texel and 3 columns short of a whole invocation; heights end in partial strips.
    for (const auto& [w, h, border] : {std::tuple{48, 36, false}, std::tuple{47, 37, true}, std::tuple{45, 35, true}}) {
      const image::Image img = picture(w, h, border ? 2u : 1u, border);
      const image::Image absorb = absorbencyImage(w, h, 3);
      const Texture2D colour = Texture2D::fromImage(img, GL_RGBA8), absorbency = Texture2D::fromImage(absorb, GL_R8);
      // What the GPU sees: the 8-bit values, read back.
      const image::Image seen = colour.download(3);
      const std::vector<float> a(absorb.pixels.begin(), absorb.pixels.end());
      const ink::InkField before = ink::inkFromImage(seen, kPaper);
      for (int n : {1, 5, 100})
        for (double ir : {0.0, 1.0})
          for (double f : {0.0, 1.0})
            for (int d : {0, 3, 64})
              for (double ip : {0.5, 1000.0}) {
                ink::DiffusionOptions o;
                o.iterations = n;
                o.residual = ir;
                o.attenuation = f;
                o.ring_steps = d;
                o.absorb = ip;
                SCOPED_TRACE(testing::Message() << "n=" << n << " Ir=" << ir << " f=" << f << " d=" << d << " Ip=" << ip
                                                << " size=" << w << "x" << h << " border=" << border);
                pass.run(colour, absorbency, o, paper);
                const image::Image gpu = pass.inkAfter();
                const ink::InkField cpu = ink::diffuseInk(before, a, o);
                double max_diff = 0, sum_diff = 0, total_gpu = 0;
                for (std::size_t i = 0; i < cpu.ink.size(); ++i) {
                  ASSERT_TRUE(std::isfinite(gpu.pixels[i]) && gpu.pixels[i] >= 0.0f);
                  const double diff = std::abs(gpu.pixels[i] - cpu.ink[i]);
                  max_diff = std::max(max_diff, diff);
                  sum_diff += diff;
                  total_gpu += gpu.pixels[i];
                }
                // Float on the GPU against double on the CPU, n iterations of rounding.
                EXPECT_LT(max_diff, 2e-5);                                        // measured worst: 5.6e-6
                EXPECT_LT(sum_diff / static_cast<double>(cpu.ink.size()), 5e-6);  // measured worst: 1.3e-6
                // The boundary stage conserves ink: compare with the main-region total.
                const ink::InkField main = ink::mainDiffusionDistance(before, o);
                EXPECT_NEAR(total_gpu, main.total(), 1e-5 * std::max(main.total(), 1.0));
                worst_max = std::max(worst_max, max_diff);
                worst_mean = std::max(worst_mean, sum_diff / static_cast<double>(cpu.ink.size()));
                ++cases;
              }
    }
    EXPECT_EQ(cases, 216);
    RecordProperty(std::string("worst_max_abs_difference_") + layout, std::to_string(worst_max));
    RecordProperty(std::string("worst_mean_abs_difference_") + layout, std::to_string(worst_mean));
    std::printf("GPU (%s layout) vs CPU ink: worst max |diff| %.3g, worst mean |diff| %.3g over %d parameter sets\n",
                layout, worst_max, worst_mean, cases);
  }
}

TEST_F(InkGpu, A4096SquarePictureStaysFiniteAndConservesInk) {
  InkDiffusionPass pass;
  const image::Image img = picture(4096, 4096, 11, true);
  const Texture2D colour = Texture2D::fromImage(img, GL_RGBA8);
  const Texture2D absorbency = Texture2D::fromImage(absorbencyImage(64, 64, 4), GL_R8);
  ink::DiffusionOptions o;
  o.iterations = 2;
  o.ring_steps = 64;
  o.absorb = 1000;  // the stiff case: far more asked than there is
  pass.run(colour, absorbency, o, glm::vec3(kPaper[0], kPaper[1], kPaper[2]));
  // Conservation of the boundary stage: the main region is the CPU's (exact transform).
  const ink::InkField main = ink::mainDiffusionDistance(ink::inkFromImage(colour.download(3), kPaper), o);
  const image::Image after = pass.inkAfter();
  double total = 0;
  for (float v : after.pixels) {
    ASSERT_TRUE(std::isfinite(v) && v >= 0.0f);
    total += v;
  }
  EXPECT_NEAR(total, main.total(), 1e-5 * main.total());
}

// Ink in one corner of a larger sheet: the boundary iterations leave out the areas it
// cannot reach in n iterations (plus the d rings), and the result is still the CPU's. The
// picture (no canvas) is written only where the ink changed: everywhere else it is the
// input to the bit.
TEST_F(InkGpu, AreasTheInkCannotReachAreLeftOutAndTheResultIsUnchanged) {
  InkDiffusionPass pass;
  const glm::vec3 paper(kPaper[0], kPaper[1], kPaper[2]);
  const int w = 320, h = 224;
  image::Image img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = std::round(static_cast<float>(kPaper[c]) * 255.0f) / 255.0f;
  // Strokes in x 12…59, y 0…25: inside the first 64 × 32 area, so ink that spreads has to
  // cross into areas holding no ink at the start.
  const image::Image corner = picture(48, 26, 5, true);
  for (int y = 0; y < corner.height; ++y)
    for (int x = 0; x < corner.width; ++x)
      for (int c = 0; c < 3; ++c) img.at(12 + x, y, c) = corner.at(x, y, c);
  const image::Image absorb = absorbencyImage(w, h, 6);
  const Texture2D colour = Texture2D::fromImage(img, GL_RGBA8), absorbency = Texture2D::fromImage(absorb, GL_R8);
  const ink::InkField before = ink::inkFromImage(colour.download(3), kPaper);
  const std::vector<float> a(absorb.pixels.begin(), absorb.pixels.end());
  // The ink is marked in blocks of 8², so up to x 63, y 31; after n iterations it can reach
  // n further, and rings of undiminished ink (f = 1) d further still: exactly the areas
  // overlapping [0, 63 + n + d] × [0, 31 + n + d] are computed (none without iterations).
  const glm::ivec2 area = InkDiffusionPass::workGroupArea();
  const int areas_x = (w + area.x - 1) / area.x, areas_y = (h + area.y - 1) / area.y;
  const image::Image seen = colour.download(4);
  // The last case has strokes but no ink above the residual: its rings still change the
  // picture.
  for (const auto& [n, d, f, residual, threshold] :
       {std::tuple{5, 3, 0.6, 0.05, 0.8}, std::tuple{20, 8, 0.6, 0.05, 0.8}, std::tuple{2, 0, 0.6, 0.05, 0.8},
        std::tuple{2, 40, 1.0, 0.05, 0.8}, std::tuple{1, 3, 0.6, 0.05, 0.8}, std::tuple{0, 3, 0.6, 0.05, 0.8},
        std::tuple{0, 6, 0.9, 1.0, 0.5}}) {
    const int reach = n + d;
    const int covered = std::min(areas_x, (63 + reach) / area.x + 1) * std::min(areas_y, (31 + reach) / area.y + 1);
    const double expected = n == 0 ? 0.0 : static_cast<double>(covered) / (areas_x * areas_y);
    SCOPED_TRACE(testing::Message() << "n=" << n << " d=" << d << " f=" << f << " residual=" << residual);
    ink::DiffusionOptions o;
    o.iterations = n;
    o.ring_steps = d;
    o.attenuation = f;
    o.residual = residual;
    o.threshold = threshold;
    const image::Image out = pass.run(colour, absorbency, o, paper).download(4);
    EXPECT_DOUBLE_EQ(pass.lastActiveFraction(), expected);
    const image::Image gpu = pass.inkAfter();
    const ink::InkField cpu = ink::diffuseInk(before, a, o);
    double max_diff = 0, total_gpu = 0;
    for (std::size_t i = 0; i < cpu.ink.size(); ++i) {
      max_diff = std::max(max_diff, std::abs(static_cast<double>(gpu.pixels[i]) - cpu.ink[i]));
      total_gpu += gpu.pixels[i];
    }
    EXPECT_LT(max_diff, 2e-5);
    EXPECT_NEAR(total_gpu, cpu.total(), 1e-5 * cpu.total());
    // The picture: the CPU's to one 8-bit step, and the input itself wherever the ink did
    // not change (alpha included).
    const image::Image expected_picture = ink::applyInk(seen, before, cpu, kPaper);
    std::size_t changed = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        const bool same = cpu.ink[i] == before.ink[i];
        changed += !same;
        for (int c = 0; c < 4; ++c) {
          if (same) {
            ASSERT_EQ(out.at(x, y, c), seen.at(x, y, c)) << x << "," << y;
          }
          ASSERT_NEAR(out.at(x, y, c), expected_picture.at(x, y, c), 1.0 / 255 + 1e-4) << x << "," << y;
        }
      }
    EXPECT_GT(changed, 100u);
  }
}

// Diffusing a picture in place gives what a separate output gets, with and without a
// canvas grain.
TEST_F(InkGpu, InPlaceEqualsASeparateOutput) {
  InkDiffusionPass pass;
  const glm::vec3 paper(kPaper[0], kPaper[1], kPaper[2]);
  const image::Image img = picture(47, 37, 8, true);
  const Texture2D absorbency = Texture2D::fromImage(absorbencyImage(47, 37, 9), GL_R8);
  // The canvas: unit-variance grain, and marks of a few per cent.
  image::Image noise(47, 37, 4, 1.0f);
  std::mt19937 rng(10);
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (int y = 0; y < 37; ++y)
    for (int x = 0; x < 47; ++x) {
      noise.at(x, y, 0) = g(rng);
      noise.at(x, y, 1) = 0.03f * g(rng);
    }
  const Texture2D grain = Texture2D::fromImage(noise, GL_RG16F);
  ink::DiffusionOptions o;
  o.iterations = 3;
  o.ring_steps = 2;
  for (const bool with_grain : {false, true}) {
    SCOPED_TRACE(with_grain ? "with a grain" : "without a grain");
    const PaperTexture texture{&absorbency, {1.0f, 0.0f}, with_grain ? &grain : nullptr, 0.2f};
    const Texture2D colour = Texture2D::fromImage(img, GL_RGBA8), separate(47, 37, GL_RGBA8);
    pass.run(colour, texture, o, paper, separate);
    const Texture2D in_place = Texture2D::fromImage(img, GL_RGBA8);
    pass.run(in_place, texture, o, paper, in_place);
    const image::Image a = separate.download(4), b = in_place.download(4);
    ASSERT_EQ(a.pixels, b.pixels);
    EXPECT_NE(a.pixels, colour.download(4).pixels) << "the ink moved";
  }
}

// Animated frames: a run limited to the region where the picture changed (grown by the
// pass's dependence) gives, everywhere, what a whole run of the new picture gives, over a
// chain of changes in different places, with and without a canvas grain. Left at the
// changed pixels alone, the result is wrong around them: the growth is needed.
TEST_F(InkGpu, ARegionRunEqualsAWholeRunOfTheChangedPicture) {
  const glm::vec3 paper(kPaper[0], kPaper[1], kPaper[2]);
  const int w = 301, h = 203;
  const Texture2D absorbency = Texture2D::fromImage(absorbencyImage(64, 64, 12), GL_R8);
  image::Image noise(w, h, 4, 0.0f);
  std::mt19937 rng(13);
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      noise.at(x, y, 0) = g(rng);
      noise.at(x, y, 1) = 0.03f * g(rng);
    }
  const Texture2D grain = Texture2D::fromImage(noise, GL_RG16F);
  // Three pictures: the second and third repaint a patch (x0, y0 in image rows from the top).
  const image::Image base = picture(w, h, 14, true);
  std::vector<image::Image> frames{base};
  const std::vector<glm::ivec4> patches{{130, 60, 170, 90}, {250, 150, 301, 203}};
  for (std::size_t k = 0; k < patches.size(); ++k) {
    image::Image next = frames.back();
    const image::Image patch = picture(w, h, 15 + static_cast<unsigned>(k), false);
    const glm::ivec4& p = patches[k];
    for (int y = p.y; y < p.w; ++y)
      for (int x = p.x; x < p.z; ++x)
        for (int c = 0; c < 3; ++c) next.at(x, y, c) = patch.at(x, y, c);
    frames.push_back(next);
  }
  // Both layouts (llvmpipe's and a GPU's, see MatchesTheCpuReferenceOnTheExtremeGrid).
  for (const char* layout : {"fragment", "compute"})
    for (const auto& [n, d, absorb] : {std::tuple{5, 3, 0.3}, std::tuple{2, 0, 1000.0}, std::tuple{0, 6, 0.3}}) {
      setenv("SHANSHUI_PIXEL_PASSES", layout, 1);
      for (const bool with_grain : {false, true}) {
        SCOPED_TRACE(testing::Message() << layout << " n=" << n << " d=" << d << " absorb=" << absorb
                                        << (with_grain ? " with a grain" : ""));
        ink::DiffusionOptions o;
        o.iterations = n;
        o.ring_steps = d;
        o.absorb = absorb;
        const PaperTexture texture{&absorbency, {1.0f, 0.0f}, with_grain ? &grain : nullptr, 0.2f};
        const int grow = InkDiffusionPass::dependence(o);
        EXPECT_EQ(grow, d + 3 * n);
        for (const bool grown : {true, false}) {
          InkDiffusionPass pass;
          const Texture2D out(w, h, GL_RGBA8);
          pass.run(Texture2D::fromImage(frames[0], GL_RGBA8), texture, o, paper, out);
          std::size_t differ = 0;
          for (std::size_t k = 0; k < patches.size(); ++k) {
            // The patch in GL pixels (y from the bottom).
            const glm::ivec4& p = patches[k];
            glm::ivec4 region(p.x, h - p.w, p.z, h - p.y);
            if (grown) region += glm::ivec4(-grow, -grow, grow, grow);
            pass.run(Texture2D::fromImage(frames[k + 1], GL_RGBA8), texture, o, paper, out, nullptr, &region);
            const glm::ivec4 window = pass.lastWindow();
            EXPECT_LT((window.z - window.x) * (window.w - window.y), w * h / 2) << "a part of the picture";
            InkDiffusionPass whole;
            const Texture2D expected(w, h, GL_RGBA8);
            whole.run(Texture2D::fromImage(frames[k + 1], GL_RGBA8), texture, o, paper, expected);
            const image::Image a = expected.download(4), b = out.download(4);
            for (std::size_t i = 0; i < a.pixels.size(); ++i) differ += a.pixels[i] != b.pixels[i];
            if (grown) {
              ASSERT_EQ(differ, 0u) << "change " << k;
            }
          }
          if (!grown && n > 0) {
            EXPECT_GT(differ, 0u) << "the ink crossed the patch's edge";
          }
        }
      }
      unsetenv("SHANSHUI_PIXEL_PASSES");
    }
}

TEST_F(InkGpu, OneByOneEmptyAndFullPicturesStayFinite) {
  InkDiffusionPass pass;
  const glm::vec3 paper(kPaper[0], kPaper[1], kPaper[2]);
  ink::DiffusionOptions o;
  o.iterations = 100;
  o.absorb = 1000;
  for (const auto& [w, h, t] :
       {std::tuple{1, 1, 0.0f}, std::tuple{1, 1, 1.0f}, std::tuple{16, 9, 0.0f}, std::tuple{16, 9, 1.0f}}) {
    image::Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) img.at(x, y, c) = static_cast<float>(kPaper[c]) * t;
    const Texture2D colour = Texture2D::fromImage(img, GL_RGBA8),
                    absorbency = Texture2D::fromImage(image::Image(1, 1, 1, 1.0f), GL_R8);
    const image::Image out = pass.run(colour, absorbency, o, paper).download(3);
    for (float v : out.pixels) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f);
    // Nothing to diffuse into or from: the picture is unchanged.
    const image::Image seen = colour.download(3);
    for (std::size_t i = 0; i < out.pixels.size(); ++i) ASSERT_NEAR(out.pixels[i], seen.pixels[i], 1.0f / 255);
  }
}

}  // namespace
}  // namespace shanshui::render
