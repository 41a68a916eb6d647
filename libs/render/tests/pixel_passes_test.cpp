// The per-pixel passes as compute shaders (issue 47 item 2): on a GPU the canvas, the ink
// pass and its stroke centres, the paper effects and the motion blur run as compute
// shaders, on llvmpipe as fragment passes; both are built from the same sources
// (pixel_main.glsl). The oracle for the compute path is the fragment path: the samples
// drawn both ways on llvmpipe are the same picture.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "gl_test.h"
#include "shanshui/core/error.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/render/pixel_stage.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/scene_assets.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

class PixelPasses : public test::HeadlessGl {
 protected:
  void TearDown() override {
    unsetenv("SHANSHUI_PIXEL_PASSES");
    unsetenv("SHANSHUI_STROKES");
    test::HeadlessGl::TearDown();
  }
};

struct Drawn {
  std::vector<image::Image> frames;
  std::map<std::string, std::vector<std::string>> variants;
  double redrawn = 1.0;  // the last frame's share of the picture drawn
};

// `frames` frames of a sample at 320x240, the camera still (the sample's animated objects
// move, so later frames redraw only their region), drawn with the per-pixel passes as `stage`.
Drawn drawSample(const std::string& sample, const char* stage, int frames, std::vector<std::string> overrides = {}) {
  setenv("SHANSHUI_PIXEL_PASSES", stage, 1);
  overrides.insert(overrides.end(), {"output.width=320", "output.height=240", "objects.0.max_vertices=30000"});
  const scene::Scene s = scene::loadScene(test::sourceDir() / "samples/scenes" / (sample + ".json"), overrides);
  scene::AssetCache cache;
  InkRenderer r(s, cache.getAll(s));
  Drawn d;
  for (int i = 0; i < frames; ++i) {
    FrameStats stats;
    d.frames.push_back(r.renderImage(frameKey(s, 0, 1, 0.0), &stats, i / 24.0));
    d.redrawn = stats.redrawn;
  }
  d.variants = r.variants();
  return d;
}

bool builtWith(const Drawn& d, const std::string& pass, const std::string& define) {
  const auto it = d.variants.find(pass);
  if (it == d.variants.end()) return false;
  for (const std::string& v : it->second)
    if (v.find(define) != std::string::npos) return true;
  return false;
}

bool builtAsCompute(const Drawn& d, const std::string& pass) {
  return builtWith(d, pass, "PIXEL_COMPUTE");
}

// Mean and largest difference of two pictures (per channel, 0-1), and the share of pixels
// more than two grey levels apart.
struct Difference {
  double mean = 0, largest = 0, share_off = 0;
};

Difference differenceOf(const image::Image& a, const image::Image& b) {
  Difference d;
  const std::size_t n = a.pixels.size();
  std::size_t off = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      bool pixel_off = false;
      for (int c = 0; c < a.channels; ++c) {
        const double e = std::abs(static_cast<double>(a.at(x, y, c)) - b.at(x, y, c));
        d.mean += e;
        d.largest = std::max(d.largest, e);
        pixel_off = pixel_off || e > 2.5 / 255;
      }
      off += pixel_off ? 1 : 0;
    }
  d.mean /= static_cast<double>(n);
  d.share_off = static_cast<double>(off) / (static_cast<double>(a.width) * a.height);
  return d;
}

// Every sample but the moving boat (below): the default (canvas, strokes, mist, trees and
// dots), the painting (ten objects, water, marks, ranges), the grove, the light-colour sample
// (pigment, shadow, edges and substrate after the ink pass), the lake, the three distances
// and the ranges. Measured at 512x384: identical but for the painting (3e-6 mean) and the
// lake and level distance (7e-9: a few pixels of a bank line, where the water's height step
// is taken across the quad's row instead of the fragment stage's derivative).
TEST_F(PixelPasses, ComputeDrawsTheSamePictureAsTheFragmentPasses) {
  for (const std::string sample : {"default", "painting", "grove", "light_colour", "lake", "high_distance",
                                   "deep_distance", "level_distance", "ranges"}) {
    SCOPED_TRACE(sample);
    const Drawn fragment = drawSample(sample, "fragment", 1), compute = drawSample(sample, "compute", 1);
    EXPECT_FALSE(builtAsCompute(fragment, "ink"));
    EXPECT_TRUE(builtAsCompute(compute, "ink"));
    EXPECT_TRUE(builtAsCompute(compute, "canvas"));
    const Difference d = differenceOf(fragment.frames[0], compute.frames[0]);
    EXPECT_LT(d.mean, 1e-4);
    EXPECT_LT(d.share_off, 1e-3);
  }
}

// A boat moving over a still scene, with its motion blur: after the first frame only its
// region is redrawn, and the compute shaders must draw that rectangle (and the stroke
// centres a margin around it) as the fragment passes draw it under the scissor.
TEST_F(PixelPasses, ARedrawnRegionIsTheSameInBothStages) {
  const Drawn fragment = drawSample("moving_boat", "fragment", 3), compute = drawSample("moving_boat", "compute", 3);
  ASSERT_LT(compute.redrawn, 0.6) << "the later frames redraw only the boat's region";
  EXPECT_TRUE(builtAsCompute(compute, "ink"));
  EXPECT_EQ(compute.variants.count("motion_blur"), 1u) << "the boat's trail is drawn too";
  for (std::size_t i = 0; i < fragment.frames.size(); ++i) {
    SCOPED_TRACE(i);
    const Difference d = differenceOf(fragment.frames[i], compute.frames[i]);
    EXPECT_LT(d.mean, 1e-4);
    EXPECT_LT(d.share_off, 1e-3);
  }
  // The frames differ from each other (the boat moved), so the comparison can fail.
  EXPECT_GT(differenceOf(compute.frames[0], compute.frames[2]).largest, 0.1);
}

// Strokes gathered by each pixel from the centres near it (SHANSHUI_STROKES=gather) instead
// of stamped by each centre with atomics: the same ink, by the same expression. The default
// sample (a reach of 1 pixel at 240 high), the painting (three widths, lines.break's pressed
// strokes, water: 2), the default with the widest strokes, 32 (4), and the moving boat, whose later
// frames redraw its region only: each drawn both ways with compute passes.
TEST_F(PixelPasses, GatheredStrokesAreTheStampedOnes) {
  struct Case {
    std::string sample;
    std::vector<std::string> overrides;
    int frames;
  };
  const Case cases[] = {
      {"default", {}, 1}, {"painting", {}, 1}, {"default", {"objects.0.lines.width=32"}, 1}, {"moving_boat", {}, 3}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.sample + (c.overrides.empty() ? "" : " " + c.overrides[0]));
    setenv("SHANSHUI_STROKES", "stamp", 1);
    const Drawn stamped = drawSample(c.sample, "compute", c.frames, c.overrides);
    setenv("SHANSHUI_STROKES", "gather", 1);
    const Drawn gathered = drawSample(c.sample, "compute", c.frames, c.overrides);
    EXPECT_FALSE(builtWith(stamped, "ink", "STROKE_GATHER"));
    EXPECT_TRUE(builtWith(gathered, "ink", "STROKE_GATHER"));
    for (int i = 0; i < c.frames; ++i) {
      const Difference d = differenceOf(stamped.frames[i], gathered.frames[i]);
      EXPECT_LE(d.largest, 1.5 / 255) << "frame " << i << ": at most a grey level, from rounding";
      EXPECT_EQ(d.share_off, 0.0) << "frame " << i;
    }
  }
  // Fragment passes stamp whatever is asked; a value neither way is an error naming it.
  const Drawn fragment = drawSample("default", "fragment", 1);
  EXPECT_FALSE(builtWith(fragment, "ink", "STROKE_GATHER"));
  setenv("SHANSHUI_STROKES", "scatter", 1);
  try {
    strokesGathered();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("SHANSHUI_STROKES is 'scatter'"), std::string::npos) << e.what();
  }
}

// The fragment stage draws the surfaces a dissolved border leaves bare (the lines pass found
// nothing of the land standing there) with their own program, sorted out by the depth test
// (ink_classes.frag). The oracle: the same renderer with the debug outputs on, which shades
// every surface pixel with the whole program. The painting's borders leave about a quarter
// of its picture bare; a scene that dissolves no border builds nothing for it.
TEST_F(PixelPasses, BareLandDrawnApartIsWhatTheWholeShadingDraws) {
  setenv("SHANSHUI_PIXEL_PASSES", "fragment", 1);
  const scene::Scene s = scene::loadScene(test::sourceDir() / "samples/scenes/painting.json",
                                          {"output.width=320", "output.height=240", "objects.0.max_vertices=30000"});
  scene::AssetCache cache;
  InkRenderer r(s, cache.getAll(s));
  const image::Image apart = r.renderImage(frameKey(s, 0, 1, 0.0));
  const std::vector<std::string> variants = r.variants().at("ink");
  EXPECT_NE(std::find(variants.begin(), variants.end(), "bare land: BARE"), variants.end());
  r.setDebugOutputs(true);
  const image::Image whole = r.renderImage(frameKey(s, 0, 1, 0.0));
  for (const std::string& v : r.variants().at("ink")) EXPECT_EQ(v.find("BARE"), std::string::npos) << v;
  const Difference d = differenceOf(apart, whole);
  EXPECT_LT(d.mean, 1e-6);
  EXPECT_EQ(d.share_off, 0.0);
  // The split matters: bare land shows the paper (but for strokes and trees), and more than
  // a fifth of the land's pixels are paper-coloured.
  const image::Image positions = r.worldPositions();
  std::size_t land = 0, paper_on_land = 0;
  for (int y = 0; y < whole.height; ++y)
    for (int x = 0; x < whole.width; ++x) {
      if (positions.at(x, y, 3) < 0.5f) continue;
      ++land;
      if (std::abs(whole.at(x, y, 0) - static_cast<float>(s.output.paper.r)) < 0.03f) ++paper_on_land;
    }
  EXPECT_GT(static_cast<double>(paper_on_land), 0.2 * static_cast<double>(land));

  const scene::Scene plain = scene::loadScene(
      test::sourceDir() / "samples/scenes/default.json",
      {"output.width=160", "output.height=120", "objects.0.max_vertices=30000", "objects.0.border.mode=\"keep\""});
  ASSERT_FALSE(plain.dissolvesBorders());
  InkRenderer p(plain, cache.getAll(plain));
  for (const std::string& v : p.variants().at("ink")) EXPECT_EQ(v.find("BARE"), std::string::npos) << v;
}

TEST_F(PixelPasses, AnUnknownStageIsAnErrorNamingTheVariable) {
  setenv("SHANSHUI_PIXEL_PASSES", "vulkan", 1);
  try {
    pixelPassesAsCompute();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("SHANSHUI_PIXEL_PASSES is 'vulkan'"), std::string::npos) << e.what();
  }
  setenv("SHANSHUI_PIXEL_PASSES", "compute", 1);
  EXPECT_TRUE(pixelPassesAsCompute());
  setenv("SHANSHUI_PIXEL_PASSES", "fragment", 1);
  EXPECT_FALSE(pixelPassesAsCompute());
  unsetenv("SHANSHUI_PIXEL_PASSES");
  EXPECT_FALSE(pixelPassesAsCompute()) << "llvmpipe shades fragment passes faster";
}

}  // namespace
}  // namespace shanshui::render
