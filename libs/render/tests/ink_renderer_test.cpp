// The ink renderer against analytic answers: curvature of spheres, Eq. 2/3 tones from the
// G-buffer normals, wrinkles only off the lines, pruning and the frame cache; and a golden
// image of the sample scene.
#include "shanshui/render/ink_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "gl_test.h"
#include "scene_in_memory.h"
#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "shanshui/ink/diffusion.h"
#include "shanshui/noise/perlin.h"
#include "shanshui/noise/value_noise.h"
#include "shanshui/render/frame_params.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_object_params.h"
#include "shanshui/render/look_metrics.h"
#include "shanshui/render/shader_library.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::render {
namespace {

using nlohmann::json;

class Ink : public test::HeadlessGl {};

using test::prepare;
using test::sceneWith;

// The value below which a fraction q of v lies (v not empty).
double quantile(std::vector<double> v, double q) {
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

double median(std::vector<double> v) {
  return quantile(std::move(v), 0.5);
}

// The value of a width key (pixels at 1024 high) that draws `px` pixels in a frame `height` high.
double widthKey(double px, int height) {
  return px * 1024.0 / height;
}

// Curvature the G-buffer holds (dimensionless) at object pixels away from the silhouette.
std::vector<double> gbufferCurvature(InkRenderer& r, const OrbitCamera& cam) {
  const image::Image nc = r.normalsAndCurvature(), pos = r.worldPositions();
  std::vector<double> k;
  const glm::vec3 eye(cam.eye());
  for (int y = 0; y < nc.height; ++y) {
    for (int x = 0; x < nc.width; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      const glm::vec3 n(nc.at(x, y, 0), nc.at(x, y, 1), nc.at(x, y, 2));
      const glm::vec3 p(pos.at(x, y, 0), pos.at(x, y, 1), pos.at(x, y, 2));
      if (std::abs(glm::dot(glm::normalize(n), glm::normalize(eye - p))) < 0.3f) continue;
      k.push_back(nc.at(x, y, 3));
    }
  }
  return k;
}

TEST_F(Ink, SphereCurvatureIsOneOnEverySphereForBothEstimators) {
  // On a sphere |k| = 1/R everywhere and the feature size is R, so the dimensionless
  // curvature is 1 whatever the radius: the point of normalising curve_factor.
  for (double radius : {0.01, 1.0, 1000.0}) {
    for (const char* source : {"quadric", "cotangent", "screen"}) {
      SCOPED_TRACE(std::to_string(radius) + " " + source);
      const scene::Scene s = sceneWith({{"lines", {{"curvature", source}}}, {"shading", {{"enabled", false}}}});
      InkRenderer r(s, prepare(s, test::uvSphere(radius, 64, 128, glm::dvec3(3e5, -2e5, 40.0))));
      const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {30, 20, 1.0});
      r.render(cam, 256, 256);
      const std::vector<double> k = gbufferCurvature(r, cam);
      ASSERT_GT(k.size(), 10000u);
      EXPECT_NEAR(median(k), 1.0, std::string(source) == "screen" ? 0.1 : 0.02);
    }
  }
}

// A cube renders with six flat faces (normals split at its creases, crease_angle 40 by
// default), as a modelling tool shows it; with crease_angle 180 the same cube is shaded
// smooth, its normals bending across every face.
TEST_F(Ink, ACubeShowsFlatFacesWithNormalsSplitAtItsCreases) {
  auto flatShare = [](double crease) {
    const scene::Scene s = sceneWith({{"crease_angle", crease}, {"lines", {{"enabled", false}}}});
    InkRenderer r(s, prepare(s, test::unitCube()));
    const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {35, 25, 1.0});
    r.render(cam, 192, 192);
    const image::Image nc = r.normalsAndCurvature(), pos = r.worldPositions();
    int object = 0, flat = 0;
    for (int y = 0; y < nc.height; ++y) {
      for (int x = 0; x < nc.width; ++x) {
        if (pos.at(x, y, 3) < 0.5f) continue;
        const glm::vec3 n = glm::normalize(glm::vec3(nc.at(x, y, 0), nc.at(x, y, 1), nc.at(x, y, 2)));
        ++object;
        flat += std::max({std::abs(n.x), std::abs(n.y), std::abs(n.z)}) > 0.999f;  // an axis: a face's normal
      }
    }
    EXPECT_GT(object, 5000);
    return static_cast<double>(flat) / std::max(object, 1);
  };
  EXPECT_GT(flatShare(40.0), 0.99);
  EXPECT_LT(flatShare(180.0), 0.2);
}

TEST_F(Ink, TonesFollowEquationsTwoAndThreeFromTheNormals) {
  // No lines, no erosion, no noise: t_dw = clamp(t_d + 1 − 1) = t_d, and the tone is the
  // Gaussian-smoothed ladder of t_d, which the test recomputes from the G-buffer normal with
  // std::erf. σ = 0 gives Eq. 2 exactly (away from the thresholds).
  for (double sigma : {0.0, 0.05}) {
    SCOPED_TRACE(sigma);
    const scene::Scene s =
        sceneWith({{"lines", {{"enabled", false}}}, {"shading", {{"erosion", 0.0}, {"noise", 0.0}, {"sigma", sigma}}}});
    InkRenderer r(s, prepare(s, test::uvSphere(2.0, 64, 128)));
    r.setDebugOutputs(true);
    ASSERT_EQ(r.passesBuilt(), (std::vector<std::string>{"gbuffer", "ink"}));
    ASSERT_EQ(r.variants().at("ink"), std::vector<std::string>{"SHADING SINGLE_OBJECT DEBUG_OUTPUTS"})
        << "no line code";
    r.render(sceneCamera(s, r.worldBounds(), 1.0, {-40, 30, 1.0}), 200, 200);
    const image::Image nc = r.normalsAndCurvature();
    const image::Image pos = r.worldPositions();
    const image::Image tone = r.passTarget("ink")->colour(2).download(1);
    const scene::ShadingParams& p = s.objects[0].shading;
    const glm::dvec3 light = glm::normalize(s.light.direction);
    int checked = 0;
    double worst = 0;
    for (int y = 0; y < tone.height; ++y) {
      for (int x = 0; x < tone.width; ++x) {
        if (pos.at(x, y, 3) < 0.5f) continue;
        const glm::dvec3 n = glm::normalize(glm::dvec3(nc.at(x, y, 0), nc.at(x, y, 1), nc.at(x, y, 2)));
        const double t = std::max(glm::dot(n, light), 0.0);
        double expected = p.tones[0];
        bool near_step = false;
        for (int k = 0; k < 4; ++k) {
          const double step = sigma > 0 ? 0.5 * std::erfc(-(t - p.thresholds[k]) / (sigma * std::sqrt(2.0)))
                                        : (t > p.thresholds[k] ? 1.0 : 0.0);
          near_step |= std::abs(t - p.thresholds[k]) < 0.003;
          expected += (p.tones[k + 1] - p.tones[k]) * step;
        }
        if (sigma == 0 && near_step) continue;  // half-float normals decide the side there
        worst = std::max(worst, std::abs(tone.at(x, y, 0) - expected));
        ++checked;
      }
    }
    EXPECT_GT(checked, 8000);
    EXPECT_LT(worst, sigma > 0 ? 3e-3 : 1e-3);  // R16F output; near a step a half-float normal moves Φ
  }
}

// The erosion noise reaches the tone where the point lies: t = t_d + (1 − e·(1 − n)) − 1,
// n being the erosion noise at the point's model x and y, which the test samples itself
// from libs/noise's tile (bilinear, as the texture is read where it is magnified). It is
// sampled in the ink pass, and with strokes in their lines stage: both paths are checked.
TEST_F(Ink, ErosionNoiseErodesTheToneAtEachPointOfTheSurface) {
  const mesh::Mesh plane = test::heightGrid(41, 41, 0.05, [](double, double) { return 0.0; });
  const double erosion = 0.8, sigma = 0.15, noise_scale = 1.0;
  for (const bool strokes : {false, true}) {
    SCOPED_TRACE(strokes ? "strokes" : "no lines");
    const json lines = strokes ? json{{"width", widthKey(3.0, 200)}, {"silhouette", 0.0}} : json{{"enabled", false}};
    const scene::Scene s = sceneWith({{"up", "z"},
                                      {"lines", lines},
                                      {"shading",
                                       {{"erosion", erosion},
                                        {"noise", 0.0},
                                        {"sigma", sigma},
                                        {"noise_scale", noise_scale},
                                        {"line_value", false}}}},
                                     {{"light", {{"direction", {0.0, 0.0, 1.0}}}}, {"output", {{"fade", 0.0}}}});
    InkRenderer r(s, prepare(s, plane));
    r.setDebugOutputs(true);
    EXPECT_EQ(r.passesBuilt(), (std::vector<std::string>{"gbuffer", "ink"}));
    r.render(sceneCamera(s, r.worldBounds(), 1.0, {0, 90, 1.6}), 200, 200);
    const image::Image pos = r.worldPositions();
    const image::Image tone = r.passTarget("ink")->colour(2).download(1);
    // The tile as uploaded (texel (i, j) is the image's (i, j)) and its place on the model:
    // the mesh is drawn relative to its bounding box's centre, one tile per 4 coarse cells.
    const image::Image tile = noise::erosionNoise(256, s.seed);
    const glm::dvec3 centre = r.worldBounds().centre();
    const double radius = 0.5 * glm::length(r.worldBounds().size());
    const double per_unit = 1.0 / (noise::kErosionCells * noise_scale * radius);
    const auto noiseAt = [&](double u, double v) {
      const double x = u * 256 - 0.5, y = v * 256 - 0.5;
      const double fx = std::floor(x), fy = std::floor(y), tx = x - fx, ty = y - fy;
      const auto at = [&](double i, double j) {
        const int ii = ((static_cast<int>(i) % 256) + 256) % 256, jj = ((static_cast<int>(j) % 256) + 256) % 256;
        return std::round(tile.at(ii, jj, 0) * 255.0) / 255.0;  // stored in 8 bits
      };
      return (at(fx, fy) * (1 - tx) + at(fx + 1, fy) * tx) * (1 - ty) +
             (at(fx, fy + 1) * (1 - tx) + at(fx + 1, fy + 1) * tx) * ty;
    };
    const scene::ShadingParams& p = s.objects[0].shading;
    std::vector<double> error;
    double lo = 1.0, hi = 0.0;
    for (int y = 2; y < tone.height - 2; ++y) {
      for (int x = 2; x < tone.width - 2; ++x) {
        if (pos.at(x, y, 3) < 0.5f) continue;
        const double n = noiseAt((pos.at(x, y, 0) - centre.x) * per_unit, (pos.at(x, y, 1) - centre.y) * per_unit);
        const double t = std::clamp(1.0 - erosion * (1.0 - n), 0.0, 1.0);  // t_d = 1 under a light overhead
        double expected = p.tones[0];
        for (int k = 0; k < 4; ++k)
          expected +=
              (p.tones[k + 1] - p.tones[k]) * 0.5 * std::erfc(-(t - p.thresholds[k]) / (sigma * std::sqrt(2.0)));
        error.push_back(std::abs(tone.at(x, y, 0) - expected));
        lo = std::min(lo, static_cast<double>(tone.at(x, y, 0)));
        hi = std::max(hi, static_cast<double>(tone.at(x, y, 0)));
      }
    }
    ASSERT_GT(error.size(), 30000u) << "the plane fills the view";
    EXPECT_GT(hi - lo, 0.2) << "the noise spreads the tones";
    EXPECT_LT(median(error), 0.01);
    EXPECT_LT(quantile(error, 0.99), 0.03);
  }
}

TEST_F(Ink, WrinklesAreMappedOnlyWhereTheLinePassGaveBackground) {
  // A black wrinkle texture (t_w = 0) drives every background pixel to the darkest tone
  // C1 (σ = 0, no noise); line pixels keep the tone they have without wrinkles.
  const mesh::Mesh sphere = test::uvSphere(1.0, 48, 96);
  json object = {{"lines", {{"curve_factor", 0.0}, {"silhouette", 0.5}, {"soft_width", 0.0}, {"depth_edges", 0.0}}},
                 {"shading", {{"erosion", 0.0}, {"noise", 0.0}, {"sigma", 0.0}, {"line_value", false}}}};
  const scene::Scene plain = sceneWith(object);
  object["wrinkle"] = {{"texture", "black.png"}, {"uv", "planar"}};
  const scene::Scene wrinkled = sceneWith(object);
  auto black = std::make_shared<const image::Image>(64, 64, 1, 0.0f);
  InkRenderer a(plain, prepare(plain, sphere)), b(wrinkled, prepare(wrinkled, sphere, black));
  a.setDebugOutputs(true);
  b.setDebugOutputs(true);
  const OrbitCamera cam = sceneCamera(plain, a.worldBounds(), 1.0, {10, 10, 1.0});
  a.render(cam, 160, 160);
  b.render(cam, 160, 160);
  const image::Image line = b.passTarget("ink")->colour(1).download(2);
  const image::Image pos = b.worldPositions();
  const image::Image ta = a.passTarget("ink")->colour(2).download(1);
  const image::Image tb = b.passTarget("ink")->colour(2).download(1);
  int on_lines = 0, off_lines = 0;
  for (int y = 0; y < 160; ++y) {
    for (int x = 0; x < 160; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      if (line.at(x, y, 0) >= 0.5f) {
        EXPECT_NEAR(tb.at(x, y, 0), ta.at(x, y, 0), 1e-3) << x << "," << y;
        ++on_lines;
      } else {
        EXPECT_NEAR(tb.at(x, y, 0), wrinkled.objects[0].shading.tones[0], 1e-3) << x << "," << y;
        ++off_lines;
      }
    }
  }
  EXPECT_GT(on_lines, 500);
  EXPECT_GT(off_lines, 5000);
}

// The G-buffer's wrinkle luma over the object (channel 2 of its second target).
std::vector<float> wrinkleLuma(InkRenderer& r, const OrbitCamera& cam, int size) {
  r.render(cam, size, size);
  const image::Image surface = r.passTarget("gbuffer")->colour(1).download(4), pos = r.worldPositions();
  std::vector<float> out;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      if (pos.at(x, y, 3) > 0.5f) out.push_back(surface.at(x, y, 2));
  return out;
}

// The wrinkle luma the ink pass shades with (second channel of its tone target), on a
// plane tilted so it falls towards -(cos φ, sin φ), with a texture of 8 stripes per tile
// that vary along u (strokes along v), and the world positions. `uv`: "planar" (slope
// wrinkles computed in the ink pass), or "mesh" with the same planar UVs stored on the mesh
// (computed in the G-buffer pass).
struct StripePicture {
  image::Image luma, pos;
};

StripePicture stripePicture(const std::string& mapping, double fall_deg, double zoom,
                            const std::string& uv = "planar") {
  const double phi = glm::radians(fall_deg);
  mesh::Mesh plane =
      test::heightGrid(81, 81, 0.05, [&](double x, double y) { return 0.5 * (x * std::cos(phi) + y * std::sin(phi)); });
  if (uv == "mesh") scene::planarUvs(plane);
  auto stripes = std::make_shared<image::Image>(64, 64, 1);
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      stripes->at(x, y, 0) = static_cast<float>(0.5 + 0.5 * std::sin(2 * std::numbers::pi * 8 * (x + 0.5) / 64));
    }
  }
  const json object = {{"up", "z"},
                       {"wrinkle",
                        {{"texture", "stripes.png"},
                         {"uv", uv},
                         {"mapping", mapping},
                         {"repeat", 3},
                         {"tile_px", 512},
                         {"filter", "trilinear"}}}};
  const scene::Scene s = sceneWith(object);
  InkRenderer r(s, prepare(s, plane, stripes));
  r.setDebugOutputs(true);
  const bool in_ink = mapping == "slope" && uv == "planar";
  const auto computes = [&](const char* pass) {
    const std::vector<std::string> v = r.variants().at(pass);
    return std::any_of(v.begin(), v.end(),
                       [](const std::string& d) { return d.find("WRINKLE_SLOPE") != std::string::npos; });
  };
  EXPECT_EQ(computes("ink"), in_ink);
  EXPECT_EQ(computes("gbuffer"), mapping == "slope" && !in_ink);
  const int size = 256;
  r.render(sceneCamera(s, r.worldBounds(), 1.0, {-100, 70, zoom}), size, size);
  StripePicture out{image::Image(size, size, 1), r.worldPositions()};
  const image::Image tone = r.passTarget("ink")->colour(2).download(2);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) out.luma.at(x, y, 0) = tone.at(x, y, 1);
  if (const char* dir = std::getenv("SHANSHUI_LOOK_DIR")) {
    image::saveImage(
        out.luma, std::filesystem::path(dir) / ("stripes_" + mapping + "_" + uv + "_" + std::to_string(int(fall_deg)) +
                                                "_" + std::to_string(int(zoom * 10)) + ".png"));
  }
  return out;
}

// The direction (world x, y) across which the luma of stripePicture varies most, from the
// structure tensor of its gradient, and its wavelength in pixels, 2π √(var / mean |∇|²) for
// a sinusoid.
struct StripeMeasure {
  double across_deg = 0.0;  //!< angle of the luma's gradient from the fall line, [0, 90]
  double wavelength_px = 0.0;
};

// The measure over pixels x0 <= x < x1, y0 <= y < y1 of a luma image and its positions,
// for a fall line at `phi` radians.
StripeMeasure measureStripesIn(const image::Image& surface, const image::Image& pos, double phi, int x0, int x1, int y0,
                               int y1) {
  glm::dmat2 tensor(0.0);
  double sum = 0, sum2 = 0, grad2 = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      if (pos.at(x, y, 3) < 0.5f || pos.at(x + 1, y, 3) < 0.5f || pos.at(x, y + 1, 3) < 0.5f) continue;
      const double l = surface.at(x, y, 0);
      const glm::dvec2 dl(surface.at(x + 1, y, 0) - l, surface.at(x, y + 1, 0) - l);
      const glm::dvec2 p0(pos.at(x, y, 0), pos.at(x, y, 1));
      const glm::dmat2 a(glm::dvec2(pos.at(x + 1, y, 0), pos.at(x + 1, y, 1)) - p0,
                         glm::dvec2(pos.at(x, y + 1, 0), pos.at(x, y + 1, 1)) - p0);
      const glm::dvec2 g = glm::inverse(glm::transpose(a)) * dl;  // dl = aᵀ g
      tensor += glm::outerProduct(g, g);
      sum += l;
      sum2 += l * l;
      grad2 += glm::dot(dl, dl);
      ++n;
    }
  }
  StripeMeasure m;
  // The tensor's main axis: angle θ with tan 2θ = 2 J_xy / (J_xx − J_yy).
  const double theta = 0.5 * std::atan2(2 * tensor[0][1], tensor[0][0] - tensor[1][1]);
  const double between = std::abs(std::remainder(theta - phi, std::numbers::pi));
  m.across_deg = glm::degrees(std::min(between, std::numbers::pi - between));
  const double mean = sum / n, var = sum2 / n - mean * mean;
  m.wavelength_px = 2 * std::numbers::pi * std::sqrt(var / (grad2 / n));
  return m;
}

StripeMeasure measureStripes(const std::string& mapping, double fall_deg, double zoom) {
  const StripePicture picture = stripePicture(mapping, fall_deg, zoom);
  const int size = picture.luma.width;  // the middle, away from the plane's edges
  return measureStripesIn(picture.luma, picture.pos, glm::radians(fall_deg), size / 4, 3 * size / 4, size / 4,
                          3 * size / 4);
}

// Cun strokes follow the slope: with `slope` the luma varies across the fall line (its
// strokes run down it) whichever way the plane falls; with `uv` it varies along world x
// whatever the plane does. And their size on screen stays within the two octaves' range
// as the camera zooms, where the UV-mapped stripes grow with the zoom.
TEST_F(Ink, SlopeWrinklesRunDownTheFallLineAtASizeFixedOnScreen) {
  for (const double fall : {0.0, 60.0, 135.0}) {
    SCOPED_TRACE(fall);
    const StripeMeasure slope = measureStripes("slope", fall, 1.0);
    std::printf("fall %.0f°: gradient %.1f° from the fall line\n", fall, slope.across_deg);
    EXPECT_GT(slope.across_deg, 80.0) << "the gradient runs across the fall line";
  }
  EXPECT_LT(measureStripes("uv", 0.0, 1.0).across_deg, 10.0) << "UV stripes ignore the slope: they vary along x";
  std::vector<double> slope_px, uv_px;
  for (const double zoom : {1.0, 1.7, 2.9}) {
    slope_px.push_back(measureStripes("slope", 0.0, zoom).wavelength_px);
    uv_px.push_back(measureStripes("uv", 0.0, zoom).wavelength_px);
  }
  std::printf("stripe wavelength at zoom 1, 1.7, 2.9: slope %.1f %.1f %.1f px, uv %.1f %.1f %.1f px\n", slope_px[0],
              slope_px[1], slope_px[2], uv_px[0], uv_px[1], uv_px[2]);
  // 8 stripes per tile, tiles of 0.71-1.41 × 128 px (tile_px 512 at 256 high) weighed most.
  for (const double px : slope_px) {
    EXPECT_GT(px, 128.0 / 8 / 2);
    EXPECT_LT(px, 128.0 / 8 * 2);
  }
  EXPECT_LT(*std::max_element(slope_px.begin(), slope_px.end()) / *std::min_element(slope_px.begin(), slope_px.end()),
            1.6);
  EXPECT_GT(uv_px[2] / uv_px[0], 2.2) << "the UV mapping's stripes grow with the zoom";
}

// The ink pass computes the slope wrinkles of one object (the first with planar UVs); a
// second such object keeps them in the G-buffer. Two planes side by side, falling the same
// way: each one's strokes run down the fall line at the same size on screen.
TEST_F(Ink, SlopeWrinklesOfTwoObjectsAreComputedInTwoPlacesAlike) {
  const double phi = glm::radians(60.0);
  const mesh::Mesh plane =
      test::heightGrid(41, 41, 0.05, [&](double x, double y) { return 0.5 * (x * std::cos(phi) + y * std::sin(phi)); });
  auto stripes = std::make_shared<image::Image>(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      stripes->at(x, y, 0) = static_cast<float>(0.5 + 0.5 * std::sin(2 * std::numbers::pi * 8 * (x + 0.5) / 64));
  const json wrinkle = {{"texture", "stripes.png"}, {"uv", "planar"}, {"mapping", "slope"}, {"tile_px", 512}};
  const json j = {
      {"objects",
       json::array(
           {{{"mesh", "left"}, {"up", "z"}, {"wrinkle", wrinkle}},
            {{"mesh", "right"}, {"up", "z"}, {"wrinkle", wrinkle}, {"transform", {{"translate", {2.2, 0, 0}}}}}})}};
  const scene::Scene s = scene::parseScene(j, "test", ".");
  std::vector<scene::LoadedObject> loaded;
  for (const scene::Object& o : s.objects)
    loaded.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(plane, o)), stripes});
  InkRenderer r(s, loaded);
  r.setDebugOutputs(true);
  const std::vector<std::string> ink = r.variants().at("ink"), gbuffer = r.variants().at("gbuffer");
  ASSERT_NE(ink.at(0).find("WRINKLE_SLOPE"), std::string::npos) << ink.at(0);
  ASSERT_EQ(gbuffer.size(), 2u);
  EXPECT_EQ(gbuffer[0].find("WRINKLE"), std::string::npos) << gbuffer[0];
  EXPECT_NE(gbuffer[1].find("WRINKLE_SLOPE"), std::string::npos) << gbuffer[1];
  const int w = 384, h = 192;
  r.render(sceneCamera(s, r.worldBounds(), 1.0, {-90, 70, 1.0}), w, h);
  const image::Image tone = r.passTarget("ink")->colour(2).download(2), pos = r.worldPositions();
  image::Image luma(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) luma.at(x, y, 0) = tone.at(x, y, 1);
  // The left plane is object 0 (x < 1), the right one object 1; their middles.
  int left_end = 0, right_start = w;
  for (int x = 0; x < w; ++x) {
    const float px = pos.at(x, h / 2, 0);
    if (pos.at(x, h / 2, 3) > 0.5f && px < 1.0f) left_end = x;
    if (pos.at(x, h / 2, 3) > 0.5f && px > 1.2f) right_start = std::min(right_start, x);
  }
  ASSERT_GT(left_end, w / 4);
  ASSERT_LT(right_start, 3 * w / 4);
  const StripeMeasure a = measureStripesIn(luma, pos, phi, left_end / 4, left_end * 3 / 4, h / 4, 3 * h / 4);
  const StripeMeasure b = measureStripesIn(luma, pos, phi, right_start + (w - right_start) / 4,
                                           w - (w - right_start) / 4, h / 4, 3 * h / 4);
  std::printf("ink pass: %.1f° from the fall line, %.1f px; G-buffer: %.1f°, %.1f px\n", a.across_deg, a.wavelength_px,
              b.across_deg, b.wavelength_px);
  EXPECT_GT(a.across_deg, 80.0);
  EXPECT_GT(b.across_deg, 80.0);
  EXPECT_LT(std::max(a.wavelength_px, b.wavelength_px) / std::min(a.wavelength_px, b.wavelength_px), 1.25);
}

// Slope wrinkles of planar UVs come from the ink pass, from the tangent plane at the
// position it rebuilds; for any other UVs, from the G-buffer pass and the triangle's screen
// derivatives. With the same UVs on a plane both ways, they agree pixel by pixel (the
// G-buffer's path is the oracle: the test above measures it against the fall line).
TEST_F(Ink, SlopeWrinklesFromTheInkPassMatchThoseFromTheGbuffer) {
  for (const double fall : {0.0, 60.0, 135.0}) {
    for (const double zoom : {1.0, 2.9}) {
      SCOPED_TRACE(testing::Message() << "fall " << fall << ", zoom " << zoom);
      const StripePicture here = stripePicture("slope", fall, zoom, "planar");
      const StripePicture gbuffer = stripePicture("slope", fall, zoom, "mesh");
      double sum = 0.0, worst = 0.0;
      int n = 0;
      for (int y = 0; y < here.luma.height; ++y) {
        for (int x = 0; x < here.luma.width; ++x) {
          if (here.pos.at(x, y, 3) < 0.5f || gbuffer.pos.at(x, y, 3) < 0.5f) continue;
          const double d = std::abs(here.luma.at(x, y, 0) - gbuffer.luma.at(x, y, 0));
          sum += d;
          worst = std::max(worst, d);
          ++n;
        }
      }
      ASSERT_GT(n, 10000);
      std::printf("fall %.0f, zoom %.1f: |ink pass - G-buffer| mean %.4f, largest %.3f\n", fall, zoom, sum / n, worst);
      EXPECT_LT(sum / n, 0.004);
      EXPECT_LT(worst, 0.03);
    }
  }
}

TEST_F(Ink, WrinkleFilterAppliesLiveAndOnlyWhereTheTextureIsMinified) {
  // Random texels, so every mip level has detail to filter.
  auto noise = std::make_shared<image::Image>(64, 64, 1);
  for (std::size_t i = 0; i < noise->pixels.size(); ++i) {
    noise->pixels[i] = static_cast<float>((i * 2654435761u) % 1000) / 999.0f;
  }
  const mesh::Mesh sphere = test::uvSphere(1.0, 32, 64);
  for (const double repeat : {4.0, 0.02}) {  // minified (2-4 texels a pixel), magnified
    SCOPED_TRACE(repeat);
    auto with = [&](const char* filter) {
      const json wrinkle = {{"texture", "noise.png"}, {"uv", "planar"}, {"repeat", repeat}, {"filter", filter}};
      return sceneWith({{"wrinkle", wrinkle}});
    };
    const scene::Scene nearest = with("nearest"), trilinear = with("trilinear");
    InkRenderer a(nearest, prepare(nearest, sphere, noise)), b(trilinear, prepare(trilinear, sphere, noise));
    const OrbitCamera cam = sceneCamera(nearest, a.worldBounds(), 1.0, {20, 30, 1.0});
    const std::vector<float> n = wrinkleLuma(a, cam, 128), t = wrinkleLuma(b, cam, 128);
    ASSERT_EQ(n.size(), t.size());
    ASSERT_GT(n.size(), 3000u);
    double differ = 0;
    for (std::size_t i = 0; i < n.size(); ++i) differ += std::abs(n[i] - t[i]) > 1e-3 ? 1 : 0;
    if (repeat > 1)
      EXPECT_GT(differ / n.size(), 0.3) << "nearest and trilinear sample alike where minified";
    else
      EXPECT_EQ(differ, 0) << "magnified, every filter is bilinear";
    a.setScene(trilinear);  // no rebuild: the same renderer now samples trilinearly
    OrbitCamera moved = cam;
    moved.azimuth_deg += 1e-9;  // not the cached frame
    EXPECT_EQ(wrinkleLuma(a, moved, 128), wrinkleLuma(b, moved, 128));
  }
}

TEST_F(Ink, UnchangedFramesArePresentedFromTheCache) {
  const scene::Scene s = sceneWith({});
  InkRenderer r(s, prepare(s, test::uvSphere(1.0)));
  OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {0, 20, 1.0});
  FrameStats st;
  r.render(cam, 64, 64, &st);
  EXPECT_FALSE(st.cached);
  EXPECT_EQ(st.passes.size(), 2u);
  r.render(cam, 64, 64, &st);
  EXPECT_TRUE(st.cached);
  EXPECT_TRUE(st.passes.empty());
  scene::Scene changed = s;
  changed.objects[0].lines.curve_factor = 2.0;
  r.setScene(changed);
  r.render(cam, 64, 64, &st);
  EXPECT_FALSE(st.cached) << "a parameter changed";
  cam.azimuth_deg += 1;
  r.render(cam, 64, 64, &st);
  EXPECT_FALSE(st.cached) << "the camera moved";
  r.render(cam, 64, 48, &st);
  EXPECT_FALSE(st.cached) << "the size changed";
  r.render(cam, 64, 48, &st);
  ASSERT_TRUE(st.cached);
  r.reloadShaders();
  r.render(cam, 64, 48, &st);
  EXPECT_FALSE(st.cached) << "the shaders were built again";
  r.setScene(changed);
  r.render(cam, 64, 48, &st);
  EXPECT_FALSE(st.cached) << "a scene was set, even an equal one";
  // A change of variant is not a parameter change.
  changed.objects[0].lines.enabled = false;
  EXPECT_THROW(r.setScene(changed), Error);
}

TEST_F(Ink, TheSeedChangesLiveAsIfTheRendererWereBuiltWithIt) {
  // The seed draws the erosion noise, the canvas's kernels and the paper absorbency the
  // diffusion uses without a canvas: a new seed takes no rebuild, and the picture is the
  // one a renderer built with that seed makes.
  for (const json& top : {json{{"canvas", {{"type", "rice_paper"}}}},
                          json{{"diffusion", {{"ring_steps", 2}, {"iterations", 3}, {"absorb", 0.6}}}}}) {
    SCOPED_TRACE(top.dump());
    json first = top, second = top;
    first["seed"] = 1;
    second["seed"] = 7;
    const scene::Scene s1 = sceneWith({}, first), s7 = sceneWith({}, second);
    const auto loaded = prepare(s1, test::uvSphere(1.0));
    InkRenderer r(s1, loaded);
    const OrbitCamera cam = sceneCamera(s1, r.worldBounds(), 1.0, {20, 30, 1.0});
    const image::Image seed1 = r.render(cam, 96, 80).colour(0).download(3);
    r.setScene(s7);
    const image::Image live = r.render(cam, 96, 80).colour(0).download(3);
    InkRenderer fresh(s7, loaded);
    const image::Image built = fresh.render(cam, 96, 80).colour(0).download(3);
    EXPECT_EQ(live.pixels, built.pixels);
    EXPECT_NE(live.pixels, seed1.pixels) << "the seed changed nothing";
  }
}

std::vector<std::string> names(const FrameStats& st) {
  std::vector<std::string> n;
  for (const auto& p : st.passes) n.push_back(p.name);
  return n;
}

TEST_F(Ink, AnimatedObjectsAreDrawnOverACachedStaticLayer) {
  // A static sphere and a spinning square patch beside it (seed 002's states B/C).
  json j = {
      {"objects", json::array({{{"mesh", "sphere"}},
                               {{"mesh", "patch"}, {"spin", 90.0}, {"transform", {{"translate", {2.5, 0, 0}}}}}})}};
  const scene::Scene s = scene::parseScene(j, "test", ".");
  const mesh::Mesh patch = test::heightGrid(12, 12, 0.15, [](double x, double y) { return 0.1 * std::sin(3 * x + y); });
  std::vector<scene::LoadedObject> loaded = {
      {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(test::uvSphere(1.0), s.objects[0])), nullptr},
      {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(patch, s.objects[1])), nullptr}};
  InkRenderer r(s, loaded);
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {-90, 40, 1.0});
  FrameStats st;
  const image::Image t0 = r.render(cam, 128, 128, &st, true, 0.0).colour(0).download(3);
  EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer_static", "gbuffer_animated", "ink"}));
  const image::Image t1 = r.render(cam, 128, 128, &st, true, 0.25).colour(0).download(3);
  EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer_animated", "ink"})) << "the static layer is reused";
  EXPECT_NE(t0.pixels, t1.pixels) << "the patch turned";
  r.render(cam, 128, 128, &st, true, 0.25);
  EXPECT_TRUE(st.cached) << "same time, same view";
  r.setScene(s);
  r.render(cam, 128, 128, &st, true, 0.25);
  EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer_static", "gbuffer_animated", "ink"}))
      << "a scene set again draws the static layer again";
  // Oracle: the same picture from a scene where the patch is simply placed at the angle
  // it has reached (22.5 degrees), drawn without the layer.
  json still = j;
  still["objects"][1]["spin"] = 0.0;
  still["objects"][1]["transform"]["rotate"] = {0, 0, 22.5};
  const scene::Scene s2 = scene::parseScene(still, "test", ".");
  InkRenderer r2(s2, loaded);
  const image::Image ref = r2.render(cam, 128, 128, &st, true, 0.0).colour(0).download(3);
  EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer", "ink"}));
  std::size_t differ = 0;
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) differ += std::abs(ref.pixels[i] - t1.pixels[i]) > 2.0f / 255;
  EXPECT_LE(differ, ref.pixels.size() / 1000);
}

TEST_F(Ink, DiffusionRunsOnlyWhenAskedAndMatchesTheCpuReference) {
  const scene::Scene off = sceneWith({});
  InkRenderer plain(off, prepare(off, test::uvSphere(1.0)));
  EXPECT_EQ(plain.passesBuilt(), (std::vector<std::string>{"gbuffer", "ink"}));
  EXPECT_EQ(plain.passTarget("diffusion"), nullptr);

  const scene::Scene s = sceneWith({}, {{"diffusion", {{"ring_steps", 4}, {"iterations", 6}, {"absorb", 0.6}}}});
  InkRenderer r(s, prepare(s, test::uvSphere(1.0)));
  EXPECT_EQ(r.passesBuilt(), (std::vector<std::string>{"gbuffer", "ink", "diffusion"}));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {20, 30, 1.0});
  FrameStats st;
  const image::Image out = r.render(cam, 96, 80, &st).colour(0).download(3);
  ASSERT_EQ(st.passes.size(), 3u);
  EXPECT_EQ(st.passes[2].name, "diffusion");
  // The CPU reference on the picture the ink pass made, with the same absorbency (tiled
  // from the bottom-left in GL's rows, as the shader reads it).
  const image::Image before = r.passTarget("ink")->colour(0).download(3);
  const image::Image tile = r.absorbency()->download(1);
  std::vector<float> a(96 * 80);
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 96; ++x)
      a[static_cast<std::size_t>(y) * 96 + x] = tile.at(x % tile.width, tile.height - 1 - ((79 - y) % tile.height));
  const double paper[3] = {s.output.paper.x, s.output.paper.y, s.output.paper.z};
  const ink::InkField in = ink::inkFromImage(before, paper);
  const image::Image expected = ink::applyInk(before, in, ink::diffuseInk(in, a, s.diffusion), paper);
  double worst = 0;
  std::size_t changed = 0;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    worst = std::max(worst, static_cast<double>(std::abs(out.pixels[i] - expected.pixels[i])));
    changed += std::abs(out.pixels[i] - before.pixels[i]) > 2.0f / 255;
  }
  EXPECT_LE(worst, 1.0 / 255 + 1e-4) << "8-bit output";
  EXPECT_GT(changed, 300u) << "the ink spread";
}

TEST_F(Ink, SmallObjectsGetNormalLinesOnly) {
  // A sphere far away covers few pixels: curvature lines are off (curve_factor is huge, so
  // they would cover it), only the N·V rim is drawn. The key is an area at 1024 high: 5000
  // pixels of a 200-pixel frame, so the same view at 400 is small too.
  const double per_200 = 1024.0 / 200;
  const scene::Scene s = sceneWith(
      {{"lines", {{"curve_factor", 100.0}, {"small_object_px", 5000.0 * per_200 * per_200}, {"depth_edges", 0.0}}},
       {"shading", {{"enabled", false}}}});
  InkRenderer r(s, prepare(s, test::uvSphere(1.0)));
  r.setDebugOutputs(true);
  auto lineShare = [&](double zoom, int size) {
    r.render(sceneCamera(s, r.worldBounds(), 1.0, {0, 0, zoom}), size, size);
    const image::Image line = r.passTarget("ink")->colour(1).download(2);
    const image::Image pos = r.worldPositions();
    double on = 0, all = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x)
        if (pos.at(x, y, 3) > 0.5f) on += line.at(x, y, 0) > 0.5f, all += 1;
    return std::pair{on / std::max(all, 1.0), all};
  };
  const auto [near_share, near_px] = lineShare(1.0, 200);
  const auto [far_share, far_px] = lineShare(0.15, 200);
  const auto [far_share_400, far_px_400] = lineShare(0.15, 400);
  EXPECT_GT(near_px, 5000.0);
  EXPECT_LT(far_px, 5000.0);
  EXPECT_NEAR(far_px_400 / far_px, 4.0, 0.5) << "four times the pixels at twice the height";
  EXPECT_GT(near_share, 0.95);    // curvature lines everywhere
  EXPECT_LT(far_share, 0.6);      // only the rim
  EXPECT_LT(far_share_400, 0.6);  // the same picture in finer pixels
}

TEST_F(Ink, ShadersReloadFromADirectoryAndABrokenOneKeepsTheOld) {
  // The directory as the repository lays it out for the ink pass (shaders/ink/ink.frag),
  // the rest flat: a shader is found either way.
  test::TempDir dir;
  std::filesystem::create_directories(dir / "ink");
  const std::filesystem::path ink_frag = dir / "ink" / "ink.frag";
  for (const std::string& name : shaderNames()) {
    std::ofstream(name == "ink.frag" ? ink_frag : dir / name) << shaderSource(name);
  }
  setShaderDirectory(dir.path());
  const scene::Scene s = sceneWith({{"lines", {{"enabled", false}}}, {"shading", {{"enabled", false}}}});
  InkRenderer r(s, prepare(s, test::uvSphere(1.0)));
  const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {0, 20, 1.0});
  auto centre = [&] {
    const image::Image img = r.render(cam, 32, 32).colour(0).download(3);
    return glm::vec3(img.at(16, 16, 0), img.at(16, 16, 1), img.at(16, 16, 2));
  };
  const glm::vec3 before = centre();
  // Edited on disk: the ink pass paints every object pixel red.
  std::string text(shaderSource("ink.frag"));
  // The end of the surfaces' shadePixel (not PAPER's), before the shared main.
  const std::string tail = "#endif\n}\n#endif\n#include \"pixel_main.glsl\"\n";
  ASSERT_EQ(text.rfind(tail), text.size() - tail.size());
  text.insert(text.size() - tail.size() + std::string("#endif\n").size(), "  o_colour = vec4(1.0, 0.0, 0.0, 1.0);\n");
  std::ofstream(ink_frag) << text;
  r.reloadShaders();
  EXPECT_EQ(centre(), glm::vec3(1, 0, 0));
  // A broken edit: the error names the file, and the last good programs keep drawing.
  std::ofstream(ink_frag) << "#version 450 core\nvoid main() { this is not glsl; }\n";
  try {
    r.reloadShaders();
    ADD_FAILURE() << "a broken shader compiled";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ink.frag"), std::string::npos) << e.what();
  }
  EXPECT_EQ(centre(), glm::vec3(1, 0, 0));
  setShaderDirectory({});
  r.reloadShaders();
  EXPECT_EQ(centre(), before);
  // The broken shader's compile errors also reached the debug output: expected here.
  for (const std::string& m : GlContext::takeDebugMessages()) EXPECT_NE(m.find("error"), std::string::npos) << m;
}

TEST_F(Ink, ExtremeInputsGiveFinitePicturesOrClearErrors) {
  auto finite = [](const image::Image& img) {
    return std::all_of(img.pixels.begin(), img.pixels.end(),
                       [](float v) { return std::isfinite(v) && v >= 0 && v <= 1; });
  };
  const scene::Scene s = sceneWith({});
  // One triangle; a flat plane (feature size 0: no curvature lines, no NaN); a sphere
  // far from the origin kept in file coordinates; a 1x1 and a very wide output.
  mesh::Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.triangles = {{0, 1, 2}};
  const mesh::Mesh flat = test::heightGrid(20, 20, 1.0, [](double, double) { return 0.0; });
  for (const mesh::Mesh* m : std::initializer_list<const mesh::Mesh*>{&tri, &flat}) {
    InkRenderer r(s, prepare(s, *m));
    const image::Image img = r.renderImage({-60, 25, 1.0});
    EXPECT_TRUE(finite(img));
  }
  // The same with strokes broken by noise over world coordinates (lines.break) 2e4 from the
  // origin: from about 2e4 of the noise's cells (the 1-pixel frame) to 3e5 (700 pixels).
  for (const nlohmann::json& lines : {nlohmann::json::object(), nlohmann::json{{"width", 4.0}, {"break", 1.0}}}) {
    const scene::Scene far = sceneWith({{"recentre", false}, {"lines", lines}});
    InkRenderer r(far, prepare(far, test::uvSphere(1.0, 24, 48, glm::dvec3(1e4, -2e4, 50))));
    for (const auto& [w, h] : {std::pair{1, 1}, std::pair{4096, 2}, std::pair{3, 700}}) {
      const OrbitCamera cam = sceneCamera(far, r.worldBounds(), static_cast<double>(w) / h, {10, 10, 1.0});
      EXPECT_TRUE(finite(r.render(cam, w, h).colour(0).download(3))) << w << "x" << h << " " << lines;
    }
  }
  // Degenerate triangles only: the mesh is refused on upload, naming the problem.
  mesh::Mesh empty;
  empty.positions = {{0, 0, 0}};
  EXPECT_THROW(InkRenderer(s, prepare(s, empty)), Error);
}

// Renders the sample scene at 200x150 with `sets` and compares it with tests/golden/NAME.
// A missing golden fails (it is part of the repository); SHANSHUI_UPDATE_GOLDEN=1 writes
// it after an intended change (then look at the picture).
void expectGolden(const std::string& name, std::vector<std::string> sets) {
  const std::filesystem::path golden = test::sourceDir() / "tests/golden" / name;
  sets.insert(sets.begin(), {"objects.0.max_vertices=20000", "output.width=200", "output.height=150"});
  scene::Scene s = scene::loadScene(test::sourceDir() / "samples/scenes/default.json", sets);
  scene::AssetCache cache;
  InkRenderer r(s, cache.getAll(s));
  const image::Image img = r.renderImage(frameKey(s, 0, 1, 0.0));
  if (std::getenv("SHANSHUI_UPDATE_GOLDEN")) {
    image::saveImage(img, golden);
    GTEST_SKIP() << "golden image written: " << golden;
  }
  ASSERT_TRUE(std::filesystem::exists(golden))
      << "missing golden image " << golden << " (write it with SHANSHUI_UPDATE_GOLDEN=1)";
  const image::Image ref = image::loadImage(golden);
  ASSERT_EQ(ref.width, img.width);
  ASSERT_EQ(ref.height, img.height);
  double sum = 0;
  std::size_t far_off = 0;
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const double d = std::abs(img.pixels[i] - ref.pixels[i]);
    sum += d;
    far_off += d > 0.1;
  }
  // Tolerances for another rasteriser (a GPU instead of llvmpipe): small mean difference,
  // few pixels far off (edges of lines and tone steps move by a pixel).
  EXPECT_LT(sum / static_cast<double>(img.pixels.size()), 0.01);
  EXPECT_LT(far_off, img.pixels.size() / 50);
}

// The goldens made before the sample grew trees and moss dots guard the other passes
// without them; a third holds the sample as it is.
TEST_F(Ink, SampleSceneMatchesItsGoldenImage) {
  expectGolden("default_scene_200x150.png", {"objects.0.trees.enabled=false", "objects.0.dots.enabled=false"});
}

TEST_F(Ink, SampleSceneWithCanvasAndDiffusionMatchesItsGoldenImage) {
  expectGolden("default_scene_silk_diffusion_200x150.png",
               {"canvas.type=silk", "diffusion.ring_steps=3", "diffusion.iterations=5", "objects.0.trees.enabled=false",
                "objects.0.dots.enabled=false"});
}

TEST_F(Ink, SampleSceneWithTreesAndDotsMatchesItsGoldenImage) {
  expectGolden("default_scene_elements_200x150.png", {});
}

// The per-object block: every member at the offset C++ writes it to, as the driver lays
// it out, in the uniform-block variants (one object; OBJECTS of them) and in the storage
// buffer used when more objects than a uniform block holds are drawn.
class ObjectBlock : public test::HeadlessGl {};

TEST_F(ObjectBlock, DriverOffsetsAreTheCppOffsets) {
  enum class Layout { Single, Block, Storage };
  for (const Layout layout : {Layout::Single, Layout::Block, Layout::Storage}) {
    SCOPED_TRACE(layout == Layout::Single  ? "one object"
                 : layout == Layout::Block ? "uniform block"
                                           : "storage buffer");
    std::vector<std::string> defines = {"LINES", "SHADING", "WRINKLE"};
    if (layout == Layout::Single) defines.emplace_back("SINGLE_OBJECT");
    if (layout == Layout::Block) defines.emplace_back("OBJECTS=3");
    const Program p({"fullscreen.vert", "ink.frag"}, defines);
    const GLenum interface = layout == Layout::Storage ? GL_BUFFER_VARIABLE : GL_UNIFORM;
    int found = 0;
    for (const gpu::FieldOffset& f : gpu::kObjectParamsFields) {
      // Drivers name block members with or without the block's name.
      GLuint index =
          glGetProgramResourceIndex(p.id(), interface, ("Objects.objects[0]." + std::string(f.name)).c_str());
      if (index == GL_INVALID_INDEX) {
        index = glGetProgramResourceIndex(p.id(), interface, ("objects[0]." + std::string(f.name)).c_str());
      }
      if (index == GL_INVALID_INDEX) continue;  // not read by the shader: optimised away
      const GLenum property = GL_OFFSET;
      GLint offset = -1;
      glGetProgramResourceiv(p.id(), interface, index, 1, &property, 1, nullptr, &offset);
      EXPECT_EQ(static_cast<std::size_t>(offset), f.offset) << f.name;
      ++found;
    }
    // std140 and std430 blocks keep every member active, read or not.
    EXPECT_GE(found, static_cast<int>(std::size(gpu::kObjectParamsFields)) - 1);
    const GLenum block_interface = layout == Layout::Storage ? GL_SHADER_STORAGE_BLOCK : GL_UNIFORM_BLOCK;
    const GLuint block = glGetProgramResourceIndex(p.id(), block_interface, "Objects");
    ASSERT_NE(block, GL_INVALID_INDEX);
    const GLenum property = GL_BUFFER_DATA_SIZE;
    GLint size = 0;
    glGetProgramResourceiv(p.id(), block_interface, block, 1, &property, 1, nullptr, &size);
    // The block is the array: one element's stride per object (an unsized array: one).
    const std::size_t elements = layout == Layout::Block ? 3 : 1;
    EXPECT_EQ(static_cast<std::size_t>(size), elements * sizeof(gpu::ObjectParams));
  }
}

// The frame's block: every member at the offset C++ writes it to, as the driver lays it out
// (std140 keeps every member active, read or not), and the block's size.
TEST_F(ObjectBlock, FrameBlockOffsetsAreTheCppOffsets) {
  const Program p({"fullscreen.vert", "ink.frag"}, {"LINES", "SHADING", "MIST", "WATER", "SINGLE_OBJECT"});
  for (const gpu::FieldOffset& f : gpu::kFrameParamsFields) {
    GLuint index = glGetProgramResourceIndex(p.id(), GL_UNIFORM, f.name);
    if (index == GL_INVALID_INDEX)
      index = glGetProgramResourceIndex(p.id(), GL_UNIFORM, ("FrameUniforms." + std::string(f.name)).c_str());
    ASSERT_NE(index, GL_INVALID_INDEX) << f.name;
    const GLenum property = GL_OFFSET;
    GLint offset = -1;
    glGetProgramResourceiv(p.id(), GL_UNIFORM, index, 1, &property, 1, nullptr, &offset);
    EXPECT_EQ(static_cast<std::size_t>(offset), f.offset) << f.name;
  }
  const GLuint block = glGetProgramResourceIndex(p.id(), GL_UNIFORM_BLOCK, "FrameUniforms");
  ASSERT_NE(block, GL_INVALID_INDEX);
  const GLenum properties[2] = {GL_BUFFER_DATA_SIZE, GL_BUFFER_BINDING};
  GLint values[2] = {0, -1};
  glGetProgramResourceiv(p.id(), GL_UNIFORM_BLOCK, block, 2, properties, 2, nullptr, values);
  EXPECT_EQ(static_cast<std::size_t>(values[0]), sizeof(gpu::FrameParams));
  EXPECT_EQ(values[1], static_cast<GLint>(kFrameBlockBinding));
}

// The block's values against the camera they come from: the inverse is the inverse, a
// point one pixel angle above the view axis at distance 1 lands one pixel above the centre,
// the fade spans the nearest and farthest corners of the bounds (brute force), the light is
// a unit vector towards it.
TEST(FrameParams, AgreeWithTheCameraAndTheScene) {
  scene::Scene s;
  s.light.direction = {1.0, -2.0, 3.0};
  s.output.paper = {0.9, 0.85, 0.8};
  s.mist.density = 0.6;
  const mesh::Bounds bounds{{-1.0, -2.0, 0.0}, {3.0, 4.0, 1.5}};
  const std::vector<SceneObjectGpu> objects;
  OrbitCamera camera;
  camera.target = {1.0, 1.0, 0.5};
  camera.distance = 12.0;
  camera.azimuth_deg = 30.0;
  camera.elevation_deg = 25.0;
  const FrameInputs in{s, objects, bounds, camera, 640, 480};
  const gpu::FrameParams f = frameParams(in);
  const glm::mat4 product = f.u_inverse_view_projection * f.u_view_projection;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(product[c][r], c == r ? 1.0f : 0.0f, 1e-4f) << c << "," << r;
  EXPECT_NEAR(glm::distance(glm::dvec3(f.u_eye), camera.eye()), 0.0, 1e-5);
  EXPECT_EQ(f.u_viewport, glm::vec2(640.0f, 480.0f));
  const glm::dmat4 to_world = glm::inverse(glm::dmat4(camera.view()));
  auto pixelY = [&](double up) {
    const glm::vec4 clip = f.u_view_projection * glm::vec4(glm::vec3(to_world * glm::dvec4(0.0, up, -1.0, 1.0)), 1.0f);
    return (clip.y / clip.w * 0.5 + 0.5) * 480.0;
  };
  EXPECT_NEAR(pixelY(f.u_pixel_angle) - pixelY(0.0), 1.0, 1e-3);
  double nearest = 1e300, farthest = 0.0;
  for (double x : {bounds.min.x, bounds.max.x})
    for (double y : {bounds.min.y, bounds.max.y})
      for (double z : {bounds.min.z, bounds.max.z}) {
        nearest = std::min(nearest, glm::distance(glm::dvec3(x, y, z), camera.eye()));
        farthest = std::max(farthest, glm::distance(glm::dvec3(x, y, z), camera.eye()));
      }
  EXPECT_NEAR(f.u_fade_range.x, nearest, 1e-4);
  EXPECT_NEAR(f.u_fade_range.y, farthest, 1e-4);
  EXPECT_NEAR(glm::length(f.u_light_dir), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(glm::dvec3(f.u_light_dir), glm::normalize(s.light.direction)), 1.0, 1e-6);
  EXPECT_EQ(f.u_paper, glm::vec3(0.9f, 0.85f, 0.8f));
  EXPECT_FLOAT_EQ(f.u_mist.x, 0.6f);
  EXPECT_EQ(f.u_water.x, std::numeric_limits<float>::lowest());  // no water
  // The wet strokes' plane is the picture plane of the scene's own view: with the camera at
  // the scene's azimuth and elevation, the view matrix's right and up rows (glm::lookAt).
  s.camera.azimuth_deg = camera.azimuth_deg;
  s.camera.elevation_deg = camera.elevation_deg;
  const gpu::FrameParams g = frameParams(in);
  const glm::mat4 view = camera.view();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(g.u_brush_right[i], view[i][0], 1e-5f) << i;
    EXPECT_NEAR(g.u_brush_up[i], view[i][1], 1e-5f) << i;
  }
  // Turning the camera now does not move it (the strokes stay in the world); a preset's
  // elevation does (deep distance looks from 40 degrees).
  OrbitCamera turned = camera;
  turned.azimuth_deg += 50.0;
  const gpu::FrameParams t = frameParams({s, objects, bounds, turned, 640, 480});
  EXPECT_EQ(t.u_brush_right, g.u_brush_right);
  EXPECT_EQ(t.u_brush_up, g.u_brush_up);
  s.camera.preset = scene::CameraPreset::Deep;
  const gpu::FrameParams d = frameParams(in);
  EXPECT_NEAR(std::asin(glm::dot(glm::dvec3(d.u_brush_up), glm::dvec3(0.0, 0.0, 1.0))),
              std::acos(-1.0) / 2.0 - glm::radians(40.0), 1e-5);
}

class Variants : public test::HeadlessGl {};

// Every shader variant the scene keys can produce compiles and links: scenes over every
// combination of the keys that choose variants (lines on/off and their curvature source,
// shading, wrinkles, canvas type, pattern and method, diffusion, mist, dissolving borders, one or
// two objects), a renderer for each scene that brings the G-buffer, canvas or diffusion a
// variant not seen yet, and each ink program the keys can choose compiled on its own.
TEST_F(Variants, EveryCombinationTheSceneKeysCanProduceCompiles) {
  const mesh::Mesh sphere = test::uvSphere(1.0, 8, 16);
  auto wrinkle = std::make_shared<const image::Image>(8, 8, 1);
  std::set<std::string> seen;
  int built = 0, compiled = 0;
  for (int bits = 0; bits < 1 << 13; ++bits) {
    const bool lines = bits & 1, screen = bits & 2, shading = bits & 4, wrinkled = bits & 8, diffusion = bits & 16,
               two = bits & 32, elements = bits & 4096;
    const int canvas = (bits >> 6) & 3;
    const bool silk_static = bits & 256, mist = bits & 512, border = bits & 1024, splat = bits & 2048;
    if (screen && !lines) continue;
    if (silk_static && canvas != 3) continue;
    if (splat && (canvas == 0 || canvas == 3)) continue;  // the method draws rice paper and silk only
    json object = {{"mesh", "memory.obj"},
                   {"lines", {{"enabled", lines}, {"curvature", screen ? "screen" : "quadric"}}},
                   {"shading", {{"enabled", shading}}}};
    if (wrinkled) object["wrinkle"] = {{"texture", "w.png"}, {"uv", "planar"}};
    if (border) object["border"] = {{"mode", "dissolve"}};
    if (elements) object["dots"] = {{"enabled", true}};
    json j = {{"objects", json::array({object})},
              {"canvas",
               {{"type", std::array{"none", "rice_paper", "silk", "static"}[canvas]},
                {"static_pattern", silk_static ? "silk" : "rice_paper"},
                {"method", splat ? "splat" : "tiles"}}}};
    // With elements, a second object spins: the elements' layer keeps its nearness.
    if (two) j["objects"].push_back({{"mesh", "memory.obj"}, {"spin", elements ? 10.0 : 0.0}});
    if (diffusion) j["diffusion"] = {{"ring_steps", 2}, {"iterations", 1}};
    if (mist) j["mist"] = {{"density", 0.5}};
    const scene::Scene s = scene::parseScene(j, "variants", ".");
    // The ink pass's structure is its defines: compile that program alone. Any other new
    // structure needs a renderer (its passes compile their own programs).
    std::vector<std::string> keys;
    std::string ink_defines;
    for (const PassEntry& e : passList()) {
      if (!e.wanted(s)) continue;
      if (std::string(e.name) == "ink")
        ink_defines = e.structure(s);
      else
        keys.push_back(std::string(e.name) + ":" + e.structure(s));
    }
    SCOPED_TRACE(j.dump());
    if (!seen.count("ink:" + ink_defines)) {
      std::vector<std::string> defines;
      std::istringstream words(ink_defines);
      for (std::string w; words >> w;) defines.push_back(w);
      ASSERT_NO_THROW(Program({"fullscreen.vert", "ink.frag"}, defines)) << ink_defines;
      seen.insert("ink:" + ink_defines);
      ++compiled;
    }
    if (std::all_of(keys.begin(), keys.end(), [&](const std::string& k) { return seen.count(k) > 0; })) continue;
    std::vector<scene::LoadedObject> objects;
    for (const scene::Object& o : s.objects) {
      objects.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(sphere, o)),
                         o.wrinkle.texture.empty() ? nullptr : wrinkle});
    }
    std::unique_ptr<InkRenderer> r;
    ASSERT_NO_THROW(r = std::make_unique<InkRenderer>(s, objects));
    r->render(sceneCamera(s, r->worldBounds(), 1.0, {-40, 30, 1.0}), 32, 32);
    seen.insert(keys.begin(), keys.end());
    ++built;
  }
  // The tests' debug outputs on top of every other define.
  ASSERT_NO_THROW(Program({"fullscreen.vert", "ink.frag"},
                          {"LINES", "SHADING", "WRINKLE", "CANVAS", "BORDER", "MIST", "DEBUG_OUTPUTS"}));
  // Strokes: the ink pass reading them, and the lines stage with one or many objects.
  ASSERT_NO_THROW(
      Program({"fullscreen.vert", "ink.frag"}, {"LINES", "STROKES", "SHADING", "BORDER", "MIST", "DEBUG_OUTPUTS"}));
  ASSERT_NO_THROW(Program({"fullscreen.vert", "ink_lines.frag"}, {"OBJECTS=2", "BORDER", "MIST"}));
  ASSERT_NO_THROW(Program({"fullscreen.vert", "ink_lines.frag"}, {"BORDER", "MIST"}));  // in a storage buffer
  ASSERT_NO_THROW(Program({"fullscreen.vert", "ink_lines.frag"}, {"SINGLE_OBJECT"}));
  ASSERT_NO_THROW(Program({"fullscreen.vert", "ink_lines.frag"}, {"SUGGESTIVE", "OBJECTS=2", "BORDER", "MIST"}));
  ASSERT_NO_THROW(Program({"fullscreen.vert", "ink_lines.frag"},
                          {"SHADING", "OBJECTS=2", "BORDER", "MIST"}));  // the noise, indexed
  // G-buffer: SURFACE × WRINKLE × curvature kinds; ink: LINES × SHADING × WRINKLE ×
  // SINGLE_OBJECT × CANVAS; canvas: two patterns × tiles (one or more objects) or splat,
  // and static's two; diffusion: one.
  EXPECT_GE(compiled, 64);  // LINES × SHADING × WRINKLE × SINGLE_OBJECT × CANVAS × BORDER × MIST, less the impossible
  EXPECT_GE(built, 10);
}

class Look : public test::HeadlessGl {};

// Ink at each pixel: 1 − luminance / the paper's, as libs/ink measures it.
std::vector<double> inkOf(const image::Image& rgb, const glm::dvec3& paper) {
  const double paper_lum = 0.2126 * paper.x + 0.7152 * paper.y + 0.0722 * paper.z;
  std::vector<double> ink(static_cast<std::size_t>(rgb.width) * rgb.height);
  for (int y = 0; y < rgb.height; ++y) {
    for (int x = 0; x < rgb.width; ++x) {
      const double lum = 0.2126 * rgb.at(x, y, 0) + 0.7152 * rgb.at(x, y, 1) + 0.0722 * rgb.at(x, y, 2);
      ink[static_cast<std::size_t>(y) * rgb.width + x] = std::max(0.0, 1.0 - lum / paper_lum);
    }
  }
  return ink;
}

// A flat square seen from above: with `dissolve` the ink at its border is bare paper and
// well inside the falloff the picture is the one with a hard edge; with `keep` the border
// carries its outline.
TEST_F(Look, BorderDissolvesIntoPaperAndLeavesTheInsideAlone) {
  const mesh::Mesh grid = test::heightGrid(101, 101, 0.02, [](double, double) { return 0.0; });
  std::map<std::string, image::Image> pictures;
  image::Image positions;
  glm::dvec3 centre(0.0);
  scene::Scene s;
  for (const char* mode : {"keep", "dissolve"}) {
    s = sceneWith({{"border", {{"mode", mode}, {"width", 0.3}, {"roughness", 1.0}}}},
                  {{"output", {{"fade", 0.0}}}, {"light", {{"direction", {0.3, 0.2, 1.0}}}}});
    InkRenderer r(s, prepare(s, grid));
    pictures[mode] = r.render(sceneCamera(s, r.worldBounds(), 1.0, {0, 89.9, 1.0}), 200, 200).colour(0).download(3);
    positions = r.worldPositions();
    centre = r.worldBounds().centre();
  }
  const std::vector<double> keep = inkOf(pictures["keep"], s.output.paper);
  const std::vector<double> dissolve = inkOf(pictures["dissolve"], s.output.paper);
  const double half = 1.0, width = 0.3 * half;  // the grid spans 2 × 2 around its centre
  double edge_keep = 0, edge_dissolve = 0;
  int edge = 0, inside = 0;
  for (int y = 0; y < 200; ++y) {
    for (int x = 0; x < 200; ++x) {
      if (positions.at(x, y, 3) < 0.5f) continue;
      const double d =
          half - std::max(std::abs(positions.at(x, y, 0) - centre.x), std::abs(positions.at(x, y, 1) - centre.y));
      const std::size_t i = static_cast<std::size_t>(y) * 200 + x;
      if (d < 0.03 * half) {  // the outer pixel or two
        edge_keep += keep[i];
        edge_dissolve += dissolve[i];
        EXPECT_LT(dissolve[i], 0.03) << x << "," << y;
        ++edge;
      } else if (d > 2.05 * width) {  // beyond the falloff pulled in by a full width of noise
        EXPECT_NEAR(dissolve[i], keep[i], 2e-3) << x << "," << y;
        ++inside;
      }
    }
  }
  ASSERT_GT(edge, 100);
  ASSERT_GT(inside, 1000);
  EXPECT_GT(edge_keep / edge, 0.3) << "the hard edge carries its outline";
  EXPECT_LT(edge_dissolve / edge, 0.01);
}

// A sphere in mist without noise: below the mist's top the ink is gone in proportion to the
// density, above its band the picture is unchanged.
TEST_F(Look, MistLeavesTheLowGroundWhiteAndTheTopsAlone) {
  const mesh::Mesh sphere = test::uvSphere(1.0, 48, 96);
  const json top = {{"output", {{"fade", 0.0}}}};
  json misty = top;
  misty["mist"] = {{"density", 1.0}, {"height", 0.3}, {"softness", 0.2}, {"roughness", 0.0}};
  const scene::Scene plain = sceneWith(json::object(), top), fog = sceneWith(json::object(), misty);
  InkRenderer a(plain, prepare(plain, sphere)), b(fog, prepare(fog, sphere));
  EXPECT_EQ(a.variants().at("ink")[0].find("MIST"), std::string::npos);
  EXPECT_NE(b.variants().at("ink")[0].find("MIST"), std::string::npos);
  const OrbitCamera cam = sceneCamera(plain, a.worldBounds(), 1.0, {-30, 10, 1.0});
  const std::vector<double> ia = inkOf(a.render(cam, 160, 160).colour(0).download(3), plain.output.paper);
  const std::vector<double> ib = inkOf(b.render(cam, 160, 160).colour(0).download(3), plain.output.paper);
  const image::Image pos = b.worldPositions();
  int low = 0, high = 0;
  for (int y = 0; y < 160; ++y) {
    for (int x = 0; x < 160; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      const double h = (pos.at(x, y, 2) + 1.0) / 2.0;  // fraction of the height from the bottom
      const std::size_t i = static_cast<std::size_t>(y) * 160 + x;
      if (h < 0.29) {
        EXPECT_LT(ib[i], 0.01) << x << "," << y;
        ++low;
      } else if (h > 0.51) {
        EXPECT_NEAR(ib[i], ia[i], 2e-3) << x << "," << y;
        ++high;
      }
    }
  }
  EXPECT_GT(low, 500);
  EXPECT_GT(high, 2000);
}

// A Gaussian hill 1.5 high (σ = 1) on a 6 × 6 plain with a few thousandths of roughness: the
// smooth shape Eq. 1's normalisation fills.
mesh::Mesh roughHill() {
  return test::heightGrid(121, 121, 0.05, [](double x, double y) {
    const double dx = x - 3.0, dy = y - 3.0;
    return 1.5 * std::exp(-(dx * dx + dy * dy) / 2.0) + 0.004 * std::sin(7.0 * x) * std::cos(5.0 * y);
  });
}

// A ridged fractal range, 8 × 6: five octaves of Perlin noise folded into crests.
mesh::Mesh fractalRange() {
  return test::heightGrid(161, 121, 0.05, [](double x, double y) {
    double h = 0, amplitude = 1, frequency = 0.35;
    for (int k = 0; k < 5; ++k) {
      h += amplitude * (1.0 - std::abs(noise::perlin(frequency * x, frequency * y, 0.5 + k)));
      amplitude *= 0.5;
      frequency *= 2.0;
    }
    return 0.6 * h * h;
  });
}

// The sample scene's style (strokes, light tones that leave the lit slopes white, aerial
// perspective 0.6, rice paper) on a lone terrain mesh with a DEM's dissolving border and
// mist, from the deep-distance preset, at 768x576.
LookStatistics paintLook(const mesh::Mesh& land, const json& extra = json::object(), const char* border = "dissolve") {
  json top = {{"camera", {{"preset", "deep"}, {"azimuth", -60}}},
              {"output", {{"fade", 0.6}}},
              {"canvas", {{"type", "rice_paper"}}},
              {"mist", {{"density", 0.75}, {"height", 0.12}, {"softness", 0.35}}}};
  top.update(extra, true);
  const scene::Scene s = sceneWith({{"lines", {{"width", widthKey(3.5, 576)}}},
                                    {"shading", {{"tones", {0.5, 0.66, 0.8, 0.92, 1.0}}}},
                                    {"border", {{"mode", border}}}},
                                   top);
  InkRenderer r(s, prepare(s, land));
  const image::Image picture = r.render(r.camera({-60, 25, 1.0}, 768.0 / 576), 768, 576).colour(0).download(3);
  // SHANSHUI_LOOK_DIR=DIR keeps the pictures, to be judged by eye beside the numbers.
  if (const char* dir = std::getenv("SHANSHUI_LOOK_DIR")) {
    static int count = 0;
    image::saveImage(picture, std::filesystem::path(dir) / ("look_" + std::to_string(count++) + ".png"));
  }
  image::Image subject(768, 576, 1);
  const image::Image positions = r.worldPositions();
  for (std::size_t i = 0; i < subject.pixels.size(); ++i) subject.pixels[i] = positions.pixels[4 * i + 3];
  return lookStatistics(picture, s.output.paper, &subject);
}

// Issue 22's bounds on synthetic terrains in the sample's style: no straight edge longer
// than a quarter of the width (the tile's cut edges are gone), dark strokes at most 5 px
// wide on average (lines, not filled regions), and the far third of the land lighter than
// the near third (aerial perspective).
TEST_F(Look, SyntheticTerrainsReadAsPaintingsByTheNumbers) {
  for (const auto& [name, land] : std::vector<std::pair<std::string, mesh::Mesh>>{{"hill on a plain", roughHill()},
                                                                                  {"fractal range", fractalRange()}}) {
    SCOPED_TRACE(name);
    const LookStatistics look = paintLook(land);
    std::printf("%s: paper %.3f, dark share %.4f, dark width %.2f px, longest straight %.3f\n", name.c_str(),
                look.paper_share, look.dark_share, look.dark_width_px, look.longest_straight);
    EXPECT_LT(look.longest_straight, 0.25);
    EXPECT_LE(look.dark_width_px, 5.0);
    EXPECT_GT(look.dark_share, 0.0) << "some dark strokes";
    EXPECT_GT(look.paper_share, 0.5) << "mostly bare paper";
    // Aerial perspective alone: no mist (it whitens the low near ground) and a kept border
    // (the dissolving one whitens the near band, which covers more rows than the far one).
    // On the range, land of one kind fills every third; the hill's far third is its
    // shadowed crown and its near third the lit plain, so there the ratio measures the
    // light (1.36), not the distance, and is only printed.
    const LookStatistics clear = paintLook(land, {{"mist", {{"density", 0.0}}}}, "keep");
    std::printf("%s, mist off, border kept: far/near ink %.3f\n", name.c_str(), clear.far_near_ink);
    EXPECT_GT(clear.far_near_ink, 0.0);
    if (name == "fractal range") {
      EXPECT_LE(clear.far_near_ink, 0.7);
    }
  }
}

// A smooth Gaussian hill with a little roughness: Eq. 1 past its threshold covers a broad
// band of it; `thin` keeps only the crests, a small share of it, and only pixels Eq. 1
// also draws.
// The hill drawn at 240² from the line tests' view, with the debug outputs: the picture's
// ink, the line weight, the world positions, and whether the lines pass was built.
struct HillLines {
  std::vector<double> ink;
  image::Image weight, positions;
  bool strokes = false;
};

HillLines drawHillLines(const scene::Scene& s, const mesh::Mesh& hill) {
  InkRenderer r(s, prepare(s, hill));
  r.setDebugOutputs(true);
  HillLines out;
  out.strokes = r.variants().at("ink").size() > 1;
  out.ink = inkOf(r.render(sceneCamera(s, r.worldBounds(), 1.0, {-30, 35, 1.2}), 240, 240).colour(0).download(3),
                  s.output.paper);
  out.weight = r.passTarget("ink")->colour(1).download(2);
  out.positions = r.worldPositions();
  return out;
}

TEST_F(Look, ThinLinesKeepTheCrestsOfEquationOnesBands) {
  const mesh::Mesh hill = roughHill();
  std::map<bool, image::Image> weight;
  image::Image positions;
  for (const bool thin : {false, true}) {
    HillLines drawn =
        drawHillLines(sceneWith({{"lines", {{"thin", thin}, {"silhouette", 0.0}, {"depth_edges", 0.0}}}}), hill);
    weight[thin] = std::move(drawn.weight);
    positions = std::move(drawn.positions);
  }
  int object = 0, thick_lines = 0, thin_lines = 0, thin_outside = 0;
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 240; ++x) {
      if (positions.at(x, y, 3) < 0.5f) continue;
      ++object;
      const bool a = weight[false].at(x, y, 0) > 0.5f, b = weight[true].at(x, y, 0) > 0.5f;
      thick_lines += a;
      thin_lines += b;
      thin_outside += b && weight[false].at(x, y, 0) <= 0.0f;
    }
  }
  ASSERT_GT(object, 10000);
  EXPECT_GT(thick_lines, object / 20) << "Eq. 1 draws a band";
  EXPECT_LT(thin_lines, thick_lines / 3);
  EXPECT_GT(thin_lines, 0);
  EXPECT_EQ(thin_outside, 0);
}

// Mean width of the strokes (pixels with ink above 0.25, so a stroke's antialiased edge
// counts as half a pixel on each side): twice their area over their perimeter,
// which for a stroke of width w and length L ≫ w is (2wL) / (2L + 2w) ≈ w.
double meanStrokeWidth(const std::vector<double>& ink, int width, int height) {
  auto dark = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width && y < height && ink[static_cast<std::size_t>(y) * width + x] > 0.25;
  };
  double area = 0, perimeter = 0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!dark(x, y)) continue;
      ++area;
      perimeter += !dark(x - 1, y) + !dark(x + 1, y) + !dark(x, y - 1) + !dark(x, y + 1);
    }
  }
  return perimeter > 0 ? 2.0 * area / perimeter : 0.0;
}

// The hill of the test above drawn with strokes: lines, not a disc, as wide as asked
// (measured in the picture, independently of how the shader draws them), only where Eq. 1
// passes its threshold, and a lines pass that exists only when strokes are asked for.
TEST_F(Look, StrokesAreLinesOfTheWidthAskedForOnAHill) {
  const mesh::Mesh hill = roughHill();
  const json top = {{"output", {{"fade", 0.0}}}};
  std::map<double, std::vector<double>> ink;
  std::map<double, image::Image> weight;
  image::Image positions;
  for (const double width : {0.0, 2.0, 5.0}) {
    HillLines drawn =
        drawHillLines(sceneWith({{"lines", {{"width", widthKey(width, 240)}, {"taper", 1.0}, {"depth_edges", 0.0}}},
                                 {"shading", {{"enabled", false}}}},
                                top),
                      hill);
    EXPECT_EQ(drawn.strokes, width > 0) << "the lines pass is built only for strokes";
    ink[width] = std::move(drawn.ink);
    weight[width] = std::move(drawn.weight);
    positions = std::move(drawn.positions);
  }
  int object = 0, band = 0, stroked = 0, stroke_off_band = 0;
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 240; ++x) {
      if (positions.at(x, y, 3) < 0.5f) continue;
      ++object;
      const std::size_t i = static_cast<std::size_t>(y) * 240 + x;
      const bool in_band = weight[0.0].at(x, y, 0) > 0.0f;
      band += weight[0.0].at(x, y, 0) > 0.5f;
      stroked += ink[2.0][i] > 0.5;
      // A stroke may spill its half-width (1 px) past the band, no further.
      bool near_band = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int u = std::clamp(x + dx, 0, 239), v = std::clamp(y + dy, 0, 239);
          near_band = near_band || weight[0.0].at(u, v, 0) > 0.0f;
        }
      }
      stroke_off_band += ink[2.0][i] > 0.5 && !in_band && !near_band;
    }
  }
  ASSERT_GT(object, 10000);
  EXPECT_GT(band, object / 20) << "Eq. 1 draws a band";
  EXPECT_GT(stroked, 100);
  EXPECT_LT(stroked, band / 2) << "strokes are lines, not the band";
  EXPECT_EQ(stroke_off_band, 0);
  const double w2 = meanStrokeWidth(ink[2.0], 240, 240), w5 = meanStrokeWidth(ink[5.0], 240, 240);
  EXPECT_GT(w2, 1.0);
  EXPECT_LT(w2, 3.0);
  EXPECT_NEAR(w5 / w2, 2.5, 0.6) << "width follows the key: " << w2 << " and " << w5 << " px";
  EXPECT_LT(w5, 6.5);
}

// Resolution independence (issue 47): a frame twice as high is the same picture in finer
// pixels. The stroke widths, measured in the picture, double with the frame's height.
TEST_F(Look, StrokesWidenWithTheFrameHeight) {
  const mesh::Mesh hill = roughHill();
  const scene::Scene s =
      sceneWith({{"lines", {{"width", 12.0}, {"taper", 1.0}, {"far_width", 1.0}, {"depth_edges", 0.0}}},
                 {"shading", {{"enabled", false}}}},
                {{"output", {{"fade", 0.0}}}});
  InkRenderer r(s, prepare(s, hill));
  std::map<int, double> width;
  for (const int size : {240, 480}) {
    const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {-30, 35, 1.2});
    width[size] = meanStrokeWidth(inkOf(r.render(cam, size, size).colour(0).download(3), s.output.paper), size, size);
  }
  EXPECT_NEAR(width[240], 12.0 * 240 / 1024, 1.0) << "the key is pixels at 1024 high";
  EXPECT_NEAR(width[480] / width[240], 2.0, 0.35) << width[240] << " and " << width[480] << " px";
}

// lines.break: a hill's skyline seen from low down is one long outline. Without the break
// every column along it carries the stroke; with it, runs of columns several pixels long
// are left bare (a brush lifted, not pixel noise), the ink of what stays varies along it
// where the even stroke's does not, and the same camera draws the same gaps (noise fixed on
// the land, seeded by nothing that changes between frames).
TEST_F(Look, BrokenStrokesLiftAlongTheLineInRuns) {
  const mesh::Mesh hill = roughHill();
  const int size = 320;
  auto draw = [&](double line_break) {
    const scene::Scene s =
        sceneWith({{"lines", {{"width", 12.0}, {"taper", 1.0}, {"far_width", 1.0}, {"break", line_break}}},
                   {"shading", {{"enabled", false}}}},
                  {{"output", {{"fade", 0.0}}}});
    InkRenderer r(s, prepare(s, hill));
    const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {-30, 4, 1.0});
    return inkOf(r.render(cam, size, size).colour(0).download(3), s.output.paper);
  };
  const std::vector<double> even = draw(0.0), broken = draw(1.0);
  EXPECT_EQ(draw(1.0), broken) << "the same camera draws the same gaps";
  auto at = [&](const std::vector<double>& ink, int x, int y) { return ink[static_cast<std::size_t>(y) * size + x]; };
  // Columns where the even skyline stroke is (its topmost row with ink), away from the ends.
  std::vector<int> sky(size, -1);
  int first = size, last = -1;
  for (int x = 0; x < size; ++x) {
    for (int y = 0; y < size && sky[x] < 0; ++y)  // row 0 at the top
      if (at(even, x, y) > 0.5) sky[x] = y;
    if (sky[x] >= 0) first = std::min(first, x), last = std::max(last, x);
  }
  ASSERT_GT(last - first, size / 3) << "a long skyline";
  int columns = 0, bare = 0, runs = 0;
  std::vector<double> peak_even, peak_broken;  // the stroke's darkest ink in each column
  bool in_gap = false;
  for (int x = first + 8; x <= last - 8; ++x) {
    if (sky[x] < 0) continue;
    ++columns;
    double e = 0, b = 0;
    for (int y = std::max(0, sky[x] - 4); y <= std::min(size - 1, sky[x] + 4); ++y) {
      e = std::max(e, at(even, x, y));
      b = std::max(b, at(broken, x, y));
    }
    const bool gap = b < 0.2;
    bare += gap;
    runs += gap && !in_gap;
    in_gap = gap;
    peak_even.push_back(e);
    if (!gap) peak_broken.push_back(b);
  }
  ASSERT_GT(columns, 80);
  auto spread = [](const std::vector<double>& v) {
    double m = 0, q = 0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) q += (x - m) * (x - m);
    return std::sqrt(q / static_cast<double>(v.size()));
  };
  const double share = static_cast<double>(bare) / columns;
  EXPECT_GT(share, 0.04) << "the broken line has gaps";
  EXPECT_LT(share, 0.45) << "most of it stays";
  ASSERT_GT(runs, 0);
  EXPECT_GE(static_cast<double>(bare) / runs, 3.0) << "gaps are lifts of the brush, several pixels long";
  EXPECT_GT(spread(peak_broken), 2.0 * spread(peak_even) + 0.02)
      << "the pressure varies the ink: " << spread(peak_broken) << " against " << spread(peak_even);
}

// The sample scene as a whole (lines, wrinkles, shading, mist, rice paper, trees and dots):
// drawn at 512x384 and averaged over 2x2 pixels it is the picture drawn at 256x192, up to
// where its marks fall within a pixel. Oracle: the two pictures' ink, per pixel and in
// bands of rows, where the old fixed-pixel line widths made the large frame far paler.
TEST_F(Look, ASampleTwiceAsHighIsTheSamePictureInFinerPixels) {
  std::map<int, image::Image> picture;
  glm::dvec3 paper(1.0);
  for (const int h : {192, 384}) {
    const scene::Scene s =
        scene::loadScene(test::sourceDir() / "samples/scenes/default.json",
                         {"objects.0.max_vertices=20000", "output.width=" + std::to_string(h * 4 / 3),
                          "output.height=" + std::to_string(h)});
    scene::AssetCache cache;
    InkRenderer r(s, cache.getAll(s));
    picture[h] = r.renderImage(frameKey(s, 0, 1, 0.0));
    paper = s.output.paper;
  }
  const image::Image& small = picture[192];
  const image::Image& large = picture[384];
  const std::vector<double> ink_small = inkOf(small, paper);
  std::vector<double> ink_large(ink_small.size());
  {
    const std::vector<double> fine = inkOf(large, paper);
    for (int y = 0; y < small.height; ++y)
      for (int x = 0; x < small.width; ++x) {
        double sum = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) sum += fine[static_cast<std::size_t>(2 * y + dy) * large.width + 2 * x + dx];
        ink_large[static_cast<std::size_t>(y) * small.width + x] = sum / 4;
      }
  }
  double total_small = 0, total_large = 0, pixel_diff = 0, worst_band = 0;
  const int band = small.height / 8;
  for (int b = 0; b < 8; ++b) {
    double band_small = 0, band_large = 0;
    for (int y = b * band; y < (b + 1) * band; ++y)
      for (int x = 0; x < small.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * small.width + x;
        band_small += ink_small[i];
        band_large += ink_large[i];
        pixel_diff += std::abs(ink_small[i] - ink_large[i]);
      }
    total_small += band_small;
    total_large += band_large;
    worst_band = std::max(worst_band, std::abs(band_small - band_large) / (band * small.width));
  }
  const double n = static_cast<double>(ink_small.size());
  ASSERT_GT(total_small / n, 0.03) << "the sample draws ink";
  // Measured: mean ink 0.064 and 0.061, worst band 0.008, per pixel 0.015; with line widths
  // in fixed pixels 0.075 and 0.066 and a band 0.025 apart.
  EXPECT_NEAR(total_large / total_small, 1.0, 0.08) << "mean ink " << total_small / n << " and " << total_large / n;
  EXPECT_LT(worst_band, 0.015) << "a band of rows differs by this much ink on average";
  EXPECT_LT(pixel_diff / n, 0.03);
}

// A bulge on a slope that rises away from the eye, seen low: above the bulge's crest the
// picture shows the slope behind it, only a little farther (less than the 3 % jump an
// outline needs). The fold is still an occluding contour, and must be one line, not the
// row of dots the N·V test alone gives there (its band is thinner than a pixel). Oracle:
// per column, the row where the visible surface jumps from the bulge to the slope
// behind, from the world positions (the bulge's near side has x > its crest's).
TEST_F(Look, AFoldSeenEdgeOnIsOneLine) {
  const double crest = 0.55;
  const mesh::Mesh land = test::heightGrid(241, 241, 1.0 / 240, [&](double x, double) {
    return 0.35 * (1.0 - x) + 0.05 * std::exp(-(x - crest) * (x - crest) / (2 * 0.03 * 0.03));
  });
  const scene::Scene s = sceneWith({{"up", "z"},
                                    {"recentre", false},
                                    {"lines", {{"width", widthKey(2.0, 240)}, {"taper", 1.0}, {"curve_factor", 0.0}}},
                                    {"shading", {{"enabled", false}}}},
                                   {{"output", {{"fade", 0.0}}}});
  InkRenderer r(s, prepare(s, land));
  // From five times as far with a fifth of the field of view: the same picture, with every
  // depth jump a fifth as large relative to the distance (about 1.4 % here).
  OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {0, 12, 1.6});
  cam.distance *= 5.0;
  cam.fov_y_deg = glm::degrees(2.0 * std::atan(std::tan(glm::radians(cam.fov_y_deg) * 0.5) / 5.0));
  cam.enclose(r.worldBounds());
  const image::Image pic = r.render(cam, 240, 240).colour(0).download(3);
  const std::vector<double> ink = inkOf(pic, s.output.paper);
  const image::Image positions = r.worldPositions();
  int columns = 0, drawn = 0;
  double jump_sum = 0;
  for (int x = 20; x < 220; ++x) {
    // Row 0 is the top; the bulge's near side is below its crest on screen, the slope
    // behind it above.
    for (int y = 0; y + 1 < 240; ++y) {
      if (positions.at(x, y, 3) < 0.5f || positions.at(x, y + 1, 3) < 0.5f) continue;
      const double above = positions.at(x, y, 0), below = positions.at(x, y + 1, 0);
      if (!(below > crest - 0.02 && above < crest - 0.06)) continue;
      ++columns;
      const glm::dvec3 eye = cam.eye();
      const double d0 = glm::length(
          glm::dvec3(positions.at(x, y + 1, 0), positions.at(x, y + 1, 1), positions.at(x, y + 1, 2)) - eye);
      const double d1 =
          glm::length(glm::dvec3(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2)) - eye);
      jump_sum += d1 / d0 - 1;
      bool hit = false;
      for (int dy = -2; dy <= 2; ++dy) {
        const int yy = std::clamp(y + dy, 0, 239);
        hit = hit || ink[static_cast<std::size_t>(yy) * 240 + x] > 0.3;
      }
      drawn += hit;
      break;
    }
  }
  ASSERT_GT(columns, 150) << "the fold is seen across the picture";
  EXPECT_LT(jump_sum / columns, 0.03) << "the jumps must be under the outline threshold for this to test folds";
  EXPECT_GT(drawn, 0.9 * columns) << "mean jump " << jump_sum / columns;
}

// Suggestive contours on a corrugated sheet h = A cos(kx) seen from the +x side, above the
// steepest slope (no true contour anywhere). Oracle (DeCarlo et al. 2003): the radial
// curvature is zero only where h'' = 0, the inflection lines kx = π/2 + nπ, and D_w κ_r > 0
// only on those where the sheet turns away from the eye (h' > 0 there: kx = 3π/2 + 2nπ).
// Strokes must lie there and not on the other half; without the key, nothing is drawn.
TEST_F(Look, SuggestiveContoursLieOnTheInflectionsThatTurnAway) {
  const double pi = std::numbers::pi, k = 2 * pi / 0.125, amplitude = 0.6 / k;  // steepest slope 0.6
  const mesh::Mesh sheet =
      test::heightGrid(241, 241, 1.0 / 240, [&](double x, double) { return amplitude * std::cos(k * x); });
  std::map<bool, int> inked;
  std::map<bool, std::string> structure;
  int near_right = 0, near_wrong = 0;
  for (const bool on : {false, true}) {
    const scene::Scene s = sceneWith({{"up", "z"},
                                      {"lines",
                                       {{"width", widthKey(2.0, 240)},
                                        {"taper", 1.0},
                                        {"curve_factor", 0.0},
                                        {"silhouette", 0.0},
                                        {"depth_edges", 0.0},
                                        {"suggestive", on ? 0.05 : 0.0}}},
                                      {"shading", {{"enabled", false}}}},
                                     {{"output", {{"fade", 0.0}}}});
    InkRenderer r(s, prepare(s, sheet));
    EXPECT_EQ(r.variants().at("ink").back().find("SUGGESTIVE") != std::string::npos, on);
    structure[on] = InkRenderer::structureKey(s);
    const std::vector<double> ink = inkOf(
        r.render(sceneCamera(s, r.worldBounds(), 1.0, {0, 50, 1.3}), 240, 240).colour(0).download(3), s.output.paper);
    const image::Image positions = r.worldPositions();
    int checked = 0;
    for (int y = 0; y < 240; ++y) {
      for (int x = 0; x < 240; ++x) {
        if (positions.at(x, y, 3) < 0.5f) continue;
        const double wx = positions.at(x, y, 0), wz = positions.at(x, y, 2);
        // The positions are the sheet's own coordinates (checked on its height).
        if (checked++ % 97 == 0) {
          ASSERT_NEAR(wz, amplitude * std::cos(k * wx), 0.05 * amplitude);
        }
        if (ink[static_cast<std::size_t>(y) * 240 + x] < 0.3) continue;
        ++inked[on];
        if (!on) continue;
        const double phase = std::fmod(std::fmod(k * wx, 2 * pi) + 2 * pi, 2 * pi);
        near_right += std::abs(phase - 1.5 * pi) < 0.6;
        near_wrong += std::abs(phase - 0.5 * pi) < 0.6;
      }
    }
    ASSERT_GT(checked, 20000);
  }
  EXPECT_NE(structure[false], structure[true]) << "the viewer must rebuild when the lines stage's variant changes";
  EXPECT_EQ(inked[false], 0) << "nothing but suggestive contours could draw here";
  EXPECT_GT(inked[true], 600) << "about eight lines across the sheet";
  EXPECT_GT(near_right, 0.85 * inked[true]) << "wrong half: " << near_wrong;
  EXPECT_LT(near_wrong, 0.03 * inked[true]);
}

// Parallel ridges and valleys of one profile z = a·cos(x), seen across: both have the same
// |k|, so Eq. 1 draws them alike; strokes put `valley_ink` of the ridges' ink in the valleys.
TEST_F(Look, ValleyStrokesCarryValleyInkOfTheRidges) {
  const double a = 0.25;
  const mesh::Mesh waves = test::heightGrid(161, 81, 0.1, [&](double x, double) { return a * std::cos(x); });
  const scene::Scene s = sceneWith({{"lines",
                                     {{"width", widthKey(3.0, 240)},
                                      {"curve_factor", 2.0},
                                      {"valley_ink", 0.4},
                                      {"silhouette", 0.0},
                                      {"depth_edges", 0.0}}},
                                    {"shading", {{"enabled", false}}}},
                                   {{"output", {{"fade", 0.0}}}});
  InkRenderer r(s, prepare(s, waves));
  const std::vector<double> ink = inkOf(
      r.render(sceneCamera(s, r.worldBounds(), 1.0, {0, 60, 1.0}), 320, 240).colour(0).download(3), s.output.paper);
  const image::Image positions = r.worldPositions();
  const double x0 = r.worldBounds().min.x;  // where the grid's x = 0 landed (the mesh is recentred)
  std::vector<double> ridge, valley;
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 320; ++x) {
      if (positions.at(x, y, 3) < 0.5f) continue;
      // Away from the grid's cut edges, which draw lines of their own.
      const double gx = positions.at(x, y, 0) - x0, gy = positions.at(x, y, 1) - r.worldBounds().min.y;
      if (gx < 1.0 || gx > 15.0 || gy < 1.0 || gy > 7.0) continue;
      // Phase of the profile at this pixel, in (−π, π]: 0 on a ridge, ±π in a valley.
      const double phase = std::remainder(gx, 2.0 * std::numbers::pi);
      const double v = ink[static_cast<std::size_t>(y) * 320 + x];
      if (std::abs(phase) < 0.25) ridge.push_back(v);
      if (std::abs(phase) > std::numbers::pi - 0.25) valley.push_back(v);
    }
  }
  ASSERT_GT(ridge.size(), 500u);
  ASSERT_GT(valley.size(), 500u);
  // The 95th percentile: the strokes' own ink, not the paper between them.
  const double ridge_ink = quantile(ridge, 0.95), valley_ink = quantile(valley, 0.95);
  EXPECT_GT(ridge_ink, 0.5);
  EXPECT_NEAR(valley_ink / ridge_ink, 0.4, 0.1);
}

}  // namespace
}  // namespace shanshui::render

namespace shanshui::render {
namespace {

double segmentDistance(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 d = b - a;
  const double t = std::clamp(glm::dot(p - a, d) / std::max(glm::dot(d, d), 1e-12), 0.0, 1.0);
  return glm::length(p - (a + t * d));
}

// Brush strokes (issue 24) on a cube seen from a corner: ink only along the edges that a
// front face borders (the independent oracle: back-face tests on a convex solid), along
// each of them, and none along the hidden ones; the pass is built only when asked.
TEST_F(Ink, BrushStrokesDrawTheVisibleEdgesOfACubeAndOnlyThem) {
  const json object = {{"up", "z"}, {"recentre", false}, {"lines", {{"enabled", false}}}};
  json with = object;
  with["strokes"] = {{"style", "qinxian"}, {"width", 24.0}, {"ink", 1.0}, {"crease", 30.0}};
  const json top = {{"output", {{"fade", 0.0}}}};
  const scene::Scene plain = sceneWith(object, top), inked = sceneWith(with, top);
  const mesh::Mesh cube = mesh::unitCube();
  InkRenderer a(plain, prepare(plain, cube)), b(inked, prepare(inked, cube));
  EXPECT_EQ(a.passesBuilt(), (std::vector<std::string>{"gbuffer", "ink"}));
  EXPECT_EQ(b.passesBuilt(), (std::vector<std::string>{"gbuffer", "ink", "strokes"}));
  const int size = 256;
  const OrbitCamera cam = sceneCamera(inked, b.worldBounds(), 1.0, {37, 28, 0.8});
  FrameStats st;
  const image::Image before = a.render(cam, size, size).colour(0).download(3);
  const image::Image after = b.render(cam, size, size, &st).colour(0).download(3);
  ASSERT_EQ(st.passes.size(), 3u);
  EXPECT_EQ(st.passes[2].name, "strokes");

  // The oracle: project the 12 edges; an edge is visible when a face on it faces the eye.
  const glm::dmat4 vp = glm::dmat4(cam.projection(1.0)) * glm::dmat4(cam.view());
  auto px = [&](glm::dvec3 p) {
    const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
    const glm::dvec2 ndc = glm::dvec2(c) / c.w;
    return glm::dvec2((ndc.x * 0.5 + 0.5) * size, (0.5 - ndc.y * 0.5) * size);  // row 0 at the top
  };
  const glm::dvec3 eye = cam.eye();
  std::vector<std::pair<glm::dvec2, glm::dvec2>> shown, hidden;
  for (int i = 0; i < 8; ++i)
    for (int bit = 0; bit < 3; ++bit) {
      const int j = i | (1 << bit);
      if (j == i) continue;
      const glm::dvec3 p(i & 1, (i >> 1) & 1, (i >> 2) & 1), q(j & 1, (j >> 1) & 1, (j >> 2) & 1);
      // The two faces on the edge: the two other axes, at the edge's coordinates.
      bool front = false;
      for (int other = 0; other < 3; ++other) {
        if (other == bit) continue;
        glm::dvec3 n(0.0);
        n[other] = p[other] > 0.5 ? 1.0 : -1.0;
        front |= glm::dot(n, eye - p) > 0.0;
      }
      (front ? shown : hidden).emplace_back(px(p), px(q));
    }
  ASSERT_EQ(shown.size(), 9u);
  const double halfWidth = 0.5 * 24.0 * size / 1024.0;
  auto darkened = [&](int x, int y) { return before.at(x, y, 0) - after.at(x, y, 0) > 0.08f; };
  // Every darkened pixel lies on a visible edge's stroke.
  int dark = 0, stray = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!darkened(x, y)) continue;
      ++dark;
      double nearest = 1e9;
      for (const auto& [p, q] : shown) nearest = std::min(nearest, segmentDistance({x + 0.5, y + 0.5}, p, q));
      stray += nearest > halfWidth + 2.0;
    }
  EXPECT_GT(dark, 500);
  EXPECT_LE(stray, dark / 100);
  // Along each visible edge the stroke is there (all but the ends)...
  for (const auto& [p, q] : shown) {
    int samples = 0, covered = 0;
    for (double t = 0.1; t <= 0.9; t += 0.02) {
      const glm::dvec2 s = glm::mix(p, q, t);
      bool any = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = static_cast<int>(s.x) + dx, y = static_cast<int>(s.y) + dy;
          if (x >= 0 && y >= 0 && x < size && y < size) any |= darkened(x, y);
        }
      ++samples;
      covered += any;
    }
    EXPECT_GE(covered, samples * 9 / 10);
  }
  // ...and along the hidden ones, away from the visible strokes, it is not.
  int hiddenSamples = 0, hiddenInked = 0;
  for (const auto& [p, q] : hidden) {
    for (double t = 0.0; t <= 1.0; t += 0.02) {
      const glm::dvec2 s = glm::mix(p, q, t);
      double nearest = 1e9;
      for (const auto& [a2, b2] : shown) nearest = std::min(nearest, segmentDistance(s, a2, b2));
      if (nearest < halfWidth + 4.0) continue;
      ++hiddenSamples;
      hiddenInked += darkened(static_cast<int>(s.x), static_cast<int>(s.y));
    }
  }
  EXPECT_GT(hiddenSamples, 20);
  EXPECT_EQ(hiddenInked, 0);
}

// The stroke's width in the rendered image follows the style's pressure curve: a flat
// square seen from above has four border strokes (its corners turn 90°, more than linking
// bridges); across each, the inked run is even for the zither string, and thin at both
// ends and full in between for the willow leaf.
TEST_F(Ink, BrushStrokeWidthInTheImageFollowsThePressure) {
  const mesh::Mesh square = mesh::heightGrid(11, 11, 0.1, [](double, double) { return 0.0; });
  const int size = 512;
  const double width = 64.0 * size / 1024.0, min_pressure = 0.15;
  auto widths = [&](const char* style) {
    const json object = {
        {"up", "z"},
        {"recentre", false},
        {"lines", {{"enabled", false}}},
        {"shading", {{"enabled", false}}},
        {"strokes", {{"style", style}, {"width", 64.0}, {"ink", 1.0}, {"min_pressure", min_pressure}}}};
    const json top = {{"output", {{"fade", 0.0}}}};
    json bare = object;
    bare.erase("strokes");
    const scene::Scene with = sceneWith(object, top), without = sceneWith(bare, top);
    InkRenderer a(without, prepare(without, square)), b(with, prepare(with, square));
    const OrbitCamera cam = sceneCamera(with, b.worldBounds(), 1.0, {0, 89, 0.6});
    const image::Image before = a.render(cam, size, size).colour(0).download(3);
    const image::Image after = b.render(cam, size, size).colour(0).download(3);
    const glm::dmat4 vp = glm::dmat4(cam.projection(1.0)) * glm::dmat4(cam.view());
    auto px = [&](glm::dvec3 p) {
      const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
      return glm::dvec2((c.x / c.w * 0.5 + 0.5) * size, (0.5 - c.y / c.w * 0.5) * size);
    };
    const glm::dvec3 corners[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    // Per edge, the inked run across it at 17 points along it.
    std::vector<std::vector<double>> out;
    for (int e = 0; e < 4; ++e) {
      const glm::dvec2 p = px(corners[e]), q = px(corners[(e + 1) % 4]);
      const glm::dvec2 n = glm::normalize(glm::dvec2(q.y - p.y, p.x - q.x));
      std::vector<double> run;
      // Far enough from the corners that the scan does not reach the next edge's stroke.
      const double margin = 0.6 * width / glm::distance(p, q);
      EXPECT_LT(margin, 0.1);
      for (int i = 0; i <= 16; ++i) {
        const glm::dvec2 c = glm::mix(p, q, margin + (1.0 - 2.0 * margin) * i / 16.0);
        int inked = 0;
        for (double k = -width; k <= width; k += 0.5) {
          const glm::ivec2 at(glm::floor(c + k * n));
          if (at.x < 0 || at.y < 0 || at.x >= size || at.y >= size) continue;
          inked += before.at(at.x, at.y, 1) - after.at(at.x, at.y, 1) > 0.05f;
        }
        run.push_back(0.5 * inked);
      }
      out.push_back(run);
    }
    return out;
  };
  for (const auto& run : widths("qinxian")) {
    for (double w : run) EXPECT_NEAR(w, width, 0.15 * width);
  }
  // The willow leaf: one swell, thin at both ends (the scan starts a little way in, where
  // the pressure has already risen), full in between.
  for (const auto& run : widths("liuye")) {
    const auto top = std::max_element(run.begin(), run.end());
    EXPECT_NEAR(*top, width, 0.15 * width);
    EXPECT_LT(run.front(), 0.6 * *top);
    EXPECT_LT(run.back(), 0.6 * *top);
    EXPECT_GE(std::min(run.front(), run.back()), min_pressure * width) << "the brush never leaves the paper";
    for (auto it = run.begin(); it + 1 != run.end(); ++it) {
      if (it < top)
        EXPECT_GE(*(it + 1), *it - 1.5) << "rising to the swell";
      else
        EXPECT_LE(*(it + 1), *it + 1.5) << "falling after it";
    }
  }
}

// Strokes are drawn in the object's line colour (as its feature lines are): a red line
// colour gives strokes whose red stays while green and blue go.
TEST_F(Ink, BrushStrokesTakeTheObjectsLineColour) {
  const mesh::Mesh cube = mesh::unitCube();
  auto strokeTint = [&](const json& colour) {
    const json object = {{"up", "z"},
                         {"recentre", false},
                         {"lines", {{"enabled", false}, {"line_color", colour}}},
                         {"strokes", {{"style", "qinxian"}, {"width", 24.0}, {"ink", 1.0}}}};
    const json top = {{"output", {{"fade", 0.0}}}};
    json bare = object;
    bare.erase("strokes");
    const scene::Scene with = sceneWith(object, top), without = sceneWith(bare, top);
    InkRenderer a(without, prepare(without, cube)), b(with, prepare(with, cube));
    const OrbitCamera cam = sceneCamera(with, b.worldBounds(), 1.0, {37, 28, 0.8});
    const image::Image before = a.render(cam, 128, 128).colour(0).download(3);
    const image::Image after = b.render(cam, 128, 128).colour(0).download(3);
    double tint = 0.0;
    int n = 0;
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x)
        if (before.at(x, y, 1) - after.at(x, y, 1) > 0.15f) tint += after.at(x, y, 0) - after.at(x, y, 1), ++n;
    EXPECT_GT(n, 100);
    return tint / std::max(n, 1);
  };
  EXPECT_GT(strokeTint({0.9, 0.05, 0.05}), 0.2);
  EXPECT_NEAR(strokeTint({0.06, 0.06, 0.07}), 0.0, 0.03);
}

// Seed 002's render states for strokes: with a spinning cube beside, behind and in front of
// a still one, the still cube's strokes come from a layer drawn once, and each frame equals
// (to the layer's rounding) the picture drawn without the layer, from a scene where the
// spinning cube is simply placed at the angle it has reached.
TEST_F(Ink, StaticStrokesAreALayerDrawnOnceAndMatchDrawingEverything) {
  const json strokes = {{"style", "qinxian"}, {"width", 16.0}, {"ink", 1.0}, {"crease", 30.0}};
  const mesh::Mesh cube = mesh::unitCube();
  for (const glm::dvec3 at : {glm::dvec3(2.0, 0, 0), glm::dvec3(0.4, -1.8, 0.2), glm::dvec3(0.4, 1.8, 0.2)}) {
    SCOPED_TRACE(testing::Message() << "spinning cube at " << at.x << "," << at.y << "," << at.z);
    json j = {{"output", {{"fade", 0.0}}},
              {"objects", json::array({{{"mesh", "still"}, {"strokes", strokes}, {"lines", {{"enabled", false}}}},
                                       {{"mesh", "spinning"},
                                        {"spin", 60.0},
                                        {"strokes", strokes},
                                        {"lines", {{"enabled", false}}},
                                        {"transform", {{"translate", {at.x, at.y, at.z}}}}}})}};
    for (json& o : j["objects"]) o["up"] = "z";
    const scene::Scene s = scene::parseScene(j, "test", ".");
    std::vector<scene::LoadedObject> loaded;
    for (const scene::Object& o : s.objects)
      loaded.push_back({std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(cube, o)), nullptr});
    InkRenderer r(s, loaded);
    const OrbitCamera cam = sceneCamera(s, r.worldBounds(), 1.0, {-60, 25, 1.0});
    FrameStats st;
    r.render(cam, 192, 192, &st, true, 0.0);
    EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer_static", "gbuffer_animated", "ink", "strokes_static",
                                                   "strokes_animated"}));
    const image::Image t1 = r.render(cam, 192, 192, &st, true, 0.5).colour(0).download(3);
    EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer_animated", "ink", "strokes_animated"}))
        << "the still cube's strokes are not found again";
    json still = j;
    still["objects"][1]["spin"] = 0.0;
    still["objects"][1]["transform"]["rotate"] = {0, 0, 30.0};
    const scene::Scene s2 = scene::parseScene(still, "test", ".");
    InkRenderer r2(s2, loaded);
    const image::Image ref = r2.render(cam, 192, 192, &st, true, 0.0).colour(0).download(3);
    EXPECT_EQ(names(st), (std::vector<std::string>{"gbuffer", "ink", "strokes"}));
    InkRenderer bare(scene::parseScene(
                         [&] {
                           json b = still;
                           for (json& o : b["objects"]) o.erase("strokes");
                           return b;
                         }(),
                         "test", "."),
                     loaded);
    const image::Image none = bare.render(cam, 192, 192).colour(0).download(3);
    std::size_t differ = 0, inked = 0;
    for (std::size_t i = 0; i < ref.pixels.size(); ++i) {
      differ += std::abs(ref.pixels[i] - t1.pixels[i]) > 8.0f / 255;
      inked += none.pixels[i] - ref.pixels[i] > 8.0f / 255;
    }
    EXPECT_GT(inked, ref.pixels.size() / 50) << "the strokes are there to compare";
    EXPECT_LE(differ, inked / 100);
  }
}

}  // namespace
}  // namespace shanshui::render
