// The paper canvas (SPEC.md section 8, issue 7): temporal coherence and flatness, and error
// against run time for N′.
//  1. Camera paths over the sample scene (orbit, dolly 0.5×-2×, pan): the masked warping
//     error between consecutive frames (frame t−1 warped to t with the known depth and
//     camera) for the dynamic canvases, the static screen-space baseline and a plain
//     object-space texture; and the peak frequency and contrast of each through the dolly,
//     on spectra averaged over seeds, beside the estimator's own spread at a fixed view.
//     Pictures of the dolly.
//  2. N′ ∈ {8, 16, 32, 64, 128} of the splatted canvas: its GPU time on the sample scene at 1024² as
//     a ratio to its G-buffer pass (interleaved in one run), and the error of a facing
//     plane's canvas against the analytic Gabor spectrum, its variance and its excess
//     kurtosis (0 for Gaussian noise; sparse noise is spiky).
//  3. The tiles canvas (the default) beside the splatted reference for each `patch`:
//     spectrum distance on a plane, warping error on the paths of 1, cost against the
//     G-buffer at 1024x768.
//  4. Rice paper's mottle for each `mottle_cell`: its difference from computing it at
//     every pixel, and the canvas's cost.
// Writes canvas_tradeoff.md, .csv, _points.csv (for shanshui-bench's plots) and
// canvas_dolly.png. --quick: small frames, short paths, N′ ∈ {8, 32}.
//   bench_canvas_tradeoff [--out DIR] [--only coherence|impulses|tiles|mottle] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_args.h"
#include "bench_output.h"
#include "order_stats.h"
#include "shanshui/image/image_io.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/noise/canvas.h"
#include "shanshui/noise/gabor.h"
#include "shanshui/render/canvas_metrics.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
using bench::median;

// One channel of an image.
image::Image channel(const image::Image& img, int c) {
  image::Image out(img.width, img.height, 1);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) out.at(x, y, 0) = img.at(x, y, c);
  return out;
}

// What each kind shows: the canvas noise, or for the object-space texture the G-buffer's
// erosion noise (value noise fixed to the model's x, y).
enum class Kind { Silk, RicePaper, Static, ObjectSpace, TilesSilk, TilesRicePaper };
const char* kKindNames[] = {"splat silk",           "splat rice paper", "static (screen) silk",
                            "object-space texture", "tiles silk",       "tiles rice paper"};
constexpr Kind kKinds[] = {Kind::TilesSilk, Kind::TilesRicePaper, Kind::Silk,
                           Kind::RicePaper, Kind::Static,         Kind::ObjectSpace};

// The scene `s` with the canvas that `kind` shows.
scene::Scene withKind(scene::Scene s, Kind kind) {
  s.canvas.type = kind == Kind::Silk || kind == Kind::ObjectSpace || kind == Kind::TilesSilk ? scene::CanvasType::Silk
                  : kind == Kind::Static                                                     ? scene::CanvasType::Static
                                         : scene::CanvasType::RicePaper;
  s.canvas.method =
      kind == Kind::TilesSilk || kind == Kind::TilesRicePaper ? scene::CanvasMethod::Tiles : scene::CanvasMethod::Splat;
  s.canvas.static_pattern = scene::CanvasPattern::Silk;
  // The G-buffer samples the erosion noise only for a pigment wash's texture layer (the ink
  // pass samples its own): a wash makes it write the noise that this kind shows.
  if (kind == Kind::ObjectSpace)
    for (scene::Object& o : s.objects) o.pigment.name = scene::PigmentName::Ochre;
  return s;
}

// Cameras along one of the paths ("orbit", "dolly", "pan") from `base`, clip planes kept
// around the scene of radius `radius` centred at `centre`.
std::vector<render::OrbitCamera> cameraPath(const render::OrbitCamera& base, const std::string& path, int frames,
                                            const glm::dvec3& centre, double radius) {
  std::vector<render::OrbitCamera> cams;
  for (int i = 0; i < frames; ++i) {
    render::OrbitCamera c = base;
    if (path == "orbit") c.azimuth_deg += i;
    if (path == "dolly") c.distance = base.distance * 2.0 * std::pow(2.0, -2.0 * i / (frames - 1));
    if (path == "pan") {
      const glm::dvec3 right = glm::normalize(glm::cross(base.target - base.eye(), glm::dvec3(0, 0, 1)));
      c.target += right * (0.01 * radius * i);
    }
    const double to_centre = glm::length(c.eye() - centre);
    c.near_plane = std::max(to_centre - radius * 1.01, to_centre * 1e-3);
    c.far_plane = to_centre + radius * 1.01;
    cams.push_back(c);
  }
  return cams;
}

struct Frame {
  render::WarpView view;
  image::Image picture;
};

Frame renderFrame(render::InkRenderer& r, Kind kind, const render::OrbitCamera& cam, int w, int h) {
  const render::Framebuffer& fb = r.render(cam, w, h);
  Frame f;
  f.picture = fb.colour(0).download(3);
  f.view.values = kind == Kind::ObjectSpace ? channel(r.passTarget("gbuffer")->colour(1).download(4), 0)
                                            : r.passTarget("canvas")->colour(0).download(1);
  f.view.camera = cam;
  f.view.positions = render::viewPositions(r, cam);
  if (kind == Kind::ObjectSpace) {
    // Only surface pixels carry the texture (the G-buffer is not cleared behind it): the
    // rest is left out of the warp and set to the surface's mean for the spectrum.
    const image::Image surface = r.worldPositions();
    double sum = 0, n = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (surface.at(x, y, 3) > 0) {
          sum += f.view.values.at(x, y, 0);
          ++n;
        }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (surface.at(x, y, 3) <= 0) {
          f.view.positions.at(x, y, 3) = 0;
          f.view.values.at(x, y, 0) = static_cast<float>(n > 0 ? sum / n : 0.0);
        }
  }
  return f;
}

// What `kind` shows in the view with scene `s` but seed `seed` (the renderer's seed changes
// live; it is left with `s`).
image::Image seeded(render::InkRenderer& r, const scene::Scene& s, std::uint64_t seed, Kind kind,
                    const render::OrbitCamera& cam, int w, int h) {
  scene::Scene t = s;
  t.seed = seed;
  r.setScene(t);
  image::Image values;
  if (kind == Kind::ObjectSpace) {
    values = renderFrame(r, kind, cam, w, h).view.values;
  } else {
    r.render(cam, w, h);
    values = r.passTarget("canvas")->colour(0).download(1);
  }
  r.setScene(s);
  return values;
}

// Copies a centred crop of `src` into `dst` at (x0, y0), greys spread to [0, 1].
void paste(image::Image& dst, const image::Image& src, int x0, int y0, int cw, int ch, bool noise) {
  const int sx = (src.width - cw) / 2, sy = (src.height - ch) / 2;
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x)
      for (int c = 0; c < 3; ++c) {
        float v = src.at(sx + x, sy + y, std::min(c, src.channels - 1));
        if (noise) v = std::clamp(0.5f + 0.18f * v, 0.0f, 1.0f);
        dst.at(x0 + x, y0 + y, c) = v;
      }
}

double excessKurtosis(const image::Image& img) {
  double s1 = 0, s2 = 0, s4 = 0;
  const double n = static_cast<double>(img.pixels.size());
  for (float v : img.pixels) s1 += v;
  const double mean = s1 / n;
  for (float v : img.pixels) {
    const double d = v - mean;
    s2 += d * d;
    s4 += d * d * d * d;
  }
  const double var = s2 / n;
  return s4 / n / (var * var) - 3.0;
}

// Ring-averaged periodogram of the canvas on a plane seen from above filling an n² frame,
// mean over `seeds` seeds from `first`.
std::vector<double> planeSpectrum(const nlohmann::json& canvas, int n, int seeds, int first) {
  std::vector<double> mean(static_cast<std::size_t>(n / 2), 0.0);
  const mesh::Mesh plane = mesh::heightGrid(33, 33, 1.0 / 32, [](double, double) { return 0.0; });
  for (int seed = first; seed < first + seeds; ++seed) {
    scene::Scene ps =
        scene::parseScene(nlohmann::json{{"seed", seed},
                                         {"objects", nlohmann::json::array({{{"mesh", "memory.obj"},
                                                                             {"lines", {{"enabled", false}}},
                                                                             {"shading", {{"enabled", false}}}}})},
                                         {"canvas", canvas},
                                         {"output", {{"width", n}, {"height", n}, {"fade", 0.0}}}},
                          "plane", ".");
    const std::vector<scene::LoadedObject> plane_objects{
        {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(plane, ps.objects[0])), nullptr}};
    render::InkRenderer pr(ps, plane_objects);
    // Each seed from another distance, spread over one octave of zoom: a canvas whose grain
    // scales with the surface between octaves (`zoom: surface`) is measured over its whole cycle.
    const double zoom = 1.6 * std::exp2(static_cast<double>(seed - first) / seeds);
    pr.render(render::sceneCamera(ps, pr.worldBounds(), 1.0, {0, 89, zoom}), n, n);
    const std::vector<double> ring = render::radialPowerSpectrum(pr.passTarget("canvas")->colour(0).download(1));
    for (std::size_t b = 0; b < mean.size(); ++b) mean[b] += ring[b] / seeds;
  }
  return mean;
}

// Relative L2 distance between two ring spectra over the rings where `reference` is above
// 1 % of its peak.
double spectrumDistance(const std::vector<double>& a, const std::vector<double>& reference) {
  const double peak = *std::max_element(reference.begin() + 1, reference.end());
  double d2 = 0, r2 = 0;
  for (std::size_t b = 1; b < reference.size(); ++b) {
    if (reference[b] < 0.01 * peak) continue;
    d2 += (a[b] - reference[b]) * (a[b] - reference[b]);
    r2 += reference[b] * reference[b];
  }
  return std::sqrt(d2 / r2);
}

// The canvas pass's and the G-buffer's GPU time on scene `s` at w × h, and their ratio
// taken per frame: medians over `frames` − 1 frames of an orbit 2° a frame (the first,
// which draws the tile, left out).
struct CanvasCost {
  double canvas_ms = 0, gbuffer_ms = 0, ratio = 0;
};

CanvasCost canvasCost(const scene::Scene& s, const std::vector<scene::LoadedObject>& objects, int w, int h,
                      int frames) {
  render::InkRenderer r(s, objects);
  const render::OrbitCamera cam0 =
      render::sceneCamera(s, r.worldBounds(), static_cast<double>(w) / h, render::frameKey(s, 0, 1, 0.0));
  std::vector<double> canvas_ms, gbuffer_ms, ratios;
  for (int f = 0; f < frames; ++f) {
    render::OrbitCamera c = cam0;
    c.azimuth_deg += 2.0 * f;
    render::FrameStats st;
    r.render(c, w, h, &st);
    if (f == 0) continue;
    double cm = 0, gm = 0;
    for (const auto& p : st.passes) {
      if (p.name == "canvas") cm = p.gpu_ms;
      if (p.name == "gbuffer") gm = p.gpu_ms;
    }
    canvas_ms.push_back(cm);
    gbuffer_ms.push_back(gm);
    ratios.push_back(cm / gm);
  }
  return {median(canvas_ms), median(gbuffer_ms), median(ratios)};
}

// The tiles canvas beside the splatted reference for each `patch`: spectrum distance to the
// reference on a plane (silk and rice paper), warping error on the sample scene's paths,
// and cost as a ratio to the G-buffer at 1024x768 (the sample scene's own size).
void tilesSection(std::ostream& md, std::ostream& csv, bench::TradeoffPoints& points, const scene::Scene& sc,
                  const std::vector<scene::LoadedObject>& objects, bool quick) {
  const int n = quick ? 128 : 512, seeds = quick ? 2 : 8;
  const int w = quick ? 128 : 512, h = quick ? 96 : 384;
  const int cost_w = quick ? 256 : 1024, cost_h = quick ? 192 : 768, cost_frames = quick ? 3 : 9;
  md << "## Tiles against the splatted reference: error against run time for `patch`\n\n"
     << "Spectrum: relative L2 distance between the mean ring-averaged periodogram (" << seeds
     << " seeds, each seen from another distance over one octave of zoom) of each canvas on a plane filling a " << n
     << "² frame and that of the splatted canvas over "
     << "rings above 1 % of its peak (`grain` 24; silk one-way at `frequency` 0.06). The floor row is the splatted "
        "canvas against itself with other seeds: the estimator's own distance. Warping error: as in the first "
        "table, silk (`grain` 24, `frequency` 0.06) on the sample scene at "
     << w << "×" << h << ". Cost: the sample scene as shipped (rice paper) at " << cost_w << "×" << cost_h
     << ", canvas over G-buffer GPU time in the same frame, median of " << cost_frames - 1
     << " frames of an orbit (the first, which draws the tile, left out).\n\n"
     << "| canvas | silk spectrum distance | rice paper spectrum distance | orbit | dolly | pan | canvas ms | "
        "G-buffer ms | canvas ÷ G-buffer |\n|---|---|---|---|---|---|---|---|---|\n";
  csv << "section,canvas,patch,silk_distance,rice_distance,orbit,dolly,pan,canvas_ms,gbuffer_ms,ratio\n";
  const nlohmann::json silk{{"type", "silk"}, {"grain", 24}, {"frequency", 0.06}, {"mix", 0.0}};
  const nlohmann::json rice{{"type", "rice_paper"}, {"grain", 24}};
  auto with = [](nlohmann::json j, const char* method, double patch, const char* zoom) {
    j["method"] = method;
    j["patch"] = patch;
    j["zoom"] = zoom;
    return j;
  };
  const std::vector<double> silk_ref = planeSpectrum(with(silk, "splat", 2, "auto"), n, seeds, 1);
  const std::vector<double> rice_ref = planeSpectrum(with(rice, "splat", 2, "auto"), n, seeds, 1);
  struct Row {
    std::string name, method;
    double patch;
    std::string zoom;
  };
  std::vector<Row> rows{{"splat (floor: other seeds)", "splat", 2, "auto"}};
  for (const char* zoom : {"screen", "surface"}) {
    for (double patch : quick ? std::vector<double>{2, 4} : std::vector<double>{1, 1.5, 2, 3, 4}) {
      rows.push_back({"tiles, patch " + std::to_string(patch).substr(0, 3) + ", zoom " + zoom, "tiles", patch, zoom});
    }
  }
  for (const Row& row : rows) {
    const int first = row.method == "splat" ? 1 + seeds : 1;
    const double silk_d = spectrumDistance(
        planeSpectrum(with(silk, row.method.c_str(), row.patch, row.zoom.c_str()), n, seeds, first), silk_ref);
    const double rice_d = spectrumDistance(
        planeSpectrum(with(rice, row.method.c_str(), row.patch, row.zoom.c_str()), n, seeds, first), rice_ref);
    // Warping error on the sample scene.
    scene::Scene s = withKind(sc, row.method == "splat" ? Kind::Silk : Kind::TilesSilk);
    s.canvas.grain = 24;
    s.canvas.frequency = 0.06;
    s.canvas.patch = row.patch;
    s.canvas.zoom = row.zoom == "surface" ? scene::CanvasZoom::Surface : scene::CanvasZoom::Screen;
    render::InkRenderer r(s, objects);
    const render::OrbitCamera base =
        render::sceneCamera(s, r.worldBounds(), static_cast<double>(w) / h, render::frameKey(s, 0, 1, 0.0));
    const double radius = 0.5 * glm::length(r.worldBounds().size());
    std::map<std::string, double> warp;
    for (const std::string path : {"orbit", "dolly", "pan"}) {
      const int frames = quick ? 3 : path == "dolly" ? 13 : 6;
      std::vector<Frame> seen;
      for (const render::OrbitCamera& cam : cameraPath(base, path, frames, r.worldBounds().centre(), radius)) {
        seen.push_back(renderFrame(r, Kind::Silk, cam, w, h));
        if (seen.size() > 1) {
          warp[path] += render::warpingError(seen[seen.size() - 2].view, seen.back().view).relative() / (frames - 1);
        }
      }
    }
    // Cost on the sample scene as shipped.
    scene::Scene cs = sc;
    cs.canvas.method = row.method == "splat" ? scene::CanvasMethod::Splat : scene::CanvasMethod::Tiles;
    cs.canvas.patch = row.patch;
    cs.canvas.zoom = row.zoom == "surface" ? scene::CanvasZoom::Surface : scene::CanvasZoom::Screen;
    const CanvasCost cost = canvasCost(cs, objects, cost_w, cost_h, cost_frames);
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %.3f | %.3f | %.4f | %.4f | %.4f | %.1f | %.1f | %.2f |\n",
                  row.name.c_str(), silk_d, rice_d, warp["orbit"], warp["dolly"], warp["pan"], cost.canvas_ms,
                  cost.gbuffer_ms, cost.ratio);
    md << line;
    std::fputs(line, stderr);
    csv << "tiles," << row.method << "," << row.patch << "," << silk_d << "," << rice_d << "," << warp["orbit"] << ","
        << warp["dolly"] << "," << warp["pan"] << "," << cost.canvas_ms << "," << cost.gbuffer_ms << "," << cost.ratio
        << "\n";
    if (row.method == "tiles") {
      const std::string series = "tiles canvas, patch 1 .. 4 (sample scene)";
      points.add("canvas: tiles spectrum against patch", "relative L2 distance to the splatted spectrum (silk)", series,
                 true, cost.canvas_ms, silk_d);
      points.add("canvas: tiles warping against patch", "warping error through the dolly", series, true, cost.canvas_ms,
                 warp["dolly"]);
    }
  }
  md << "\n";
}

// Rice paper's mottle computed once per `mottle_cell` pixels and read bilinearly, against
// every pixel computing its own (cell 1): mean and largest difference over the mottle's
// standard deviation on a plane filling a 512² frame, and the canvas's cost on the sample
// scene at 1024x768 over the G-buffer's in the same frames.
void mottleSection(std::ostream& md, std::ostream& csv, bench::TradeoffPoints& points, const scene::Scene& sc,
                   const std::vector<scene::LoadedObject>& objects, bool quick) {
  const int n = quick ? 128 : 512;
  const int cost_w = quick ? 256 : 1024, cost_h = quick ? 192 : 768, cost_frames = quick ? 3 : 9;
  md << "## Rice paper's mottle: error against run time for `mottle_cell`\n\n"
     << "Error: the marks channel of the default rice paper without fibres and spots on a plane filling a " << n
     << "² frame, each cell's image read bilinearly against computing the mottle at every pixel (cell 1): mean and "
        "largest absolute difference, over the mottle's standard deviation. Cost: the sample scene as shipped at "
     << cost_w << "×" << cost_h << ", canvas over G-buffer GPU time in the same frame, median of " << cost_frames - 1
     << " frames of an orbit.\n\n"
     << "| mottle_cell | mean error ÷ σ | largest error ÷ σ | canvas ms | G-buffer ms | canvas ÷ G-buffer |\n"
        "|---|---|---|---|---|---|\n";
  csv << "section,mottle_cell,mean_error,largest_error,canvas_ms,gbuffer_ms,ratio\n";
  const mesh::Mesh plane = mesh::heightGrid(33, 33, 1.0 / 32, [](double, double) { return 0.0; });
  auto marks = [&](double cell) {
    scene::Scene ps = scene::parseScene(
        nlohmann::json{{"objects", nlohmann::json::array({{{"mesh", "memory.obj"},
                                                           {"lines", {{"enabled", false}}},
                                                           {"shading", {{"enabled", false}}}}})},
                       {"canvas", {{"type", "rice_paper"}, {"fibres", 0}, {"spots", 0}, {"mottle_cell", cell}}},
                       {"output", {{"width", n}, {"height", n}, {"fade", 0.0}}}},
        "plane", ".");
    const std::vector<scene::LoadedObject> plane_objects{
        {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(plane, ps.objects[0])), nullptr}};
    render::InkRenderer pr(ps, plane_objects);
    pr.render(render::sceneCamera(ps, pr.worldBounds(), 1.0, {0, 89, 1.6}), n, n);
    return channel(pr.passTarget("canvas")->colour(0).download(2), 1);
  };
  const image::Image exact = marks(1);
  double mean = 0, var = 0;
  for (float v : exact.pixels) mean += v / static_cast<double>(exact.pixels.size());
  for (float v : exact.pixels) var += (v - mean) * (v - mean) / static_cast<double>(exact.pixels.size());
  const double sd = std::sqrt(var);
  for (double cell : quick ? std::vector<double>{1, 8} : std::vector<double>{1, 2, 4, 8, 16, 32}) {
    const image::Image m = marks(cell);
    double mean_error = 0, largest = 0;
    for (std::size_t i = 0; i < m.pixels.size(); ++i) {
      const double e = std::abs(m.pixels[i] - exact.pixels[i]);
      mean_error += e / static_cast<double>(m.pixels.size());
      largest = std::max(largest, e);
    }
    scene::Scene cs = sc;
    cs.canvas.mottle_cell = cell;
    const CanvasCost cost = canvasCost(cs, objects, cost_w, cost_h, cost_frames);
    char line[256];
    std::snprintf(line, sizeof line, "| %g | %.4f | %.3f | %.1f | %.1f | %.3f |\n", cell, mean_error / sd, largest / sd,
                  cost.canvas_ms, cost.gbuffer_ms, cost.ratio);
    md << line;
    std::fputs(line, stderr);
    csv << "mottle," << cell << "," << mean_error / sd << "," << largest / sd << "," << cost.canvas_ms << ","
        << cost.gbuffer_ms << "," << cost.ratio << "\n";
    if (cell > 1) {
      points.add("canvas: mottle against its cell", "mean difference from every pixel's own, over its σ",
                 "mottle_cell 2 .. 32 (sample scene)", true, cost.canvas_ms, mean_error / sd);
    }
  }
  md << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(
      argc, argv, "bench_canvas_tradeoff [--out DIR] [--only coherence|impulses|tiles|mottle] [--quick]", {"--only"});
  const std::filesystem::path out = args.out;
  const bool quick = args.quick;
  const std::string only = args.text("--only", "");  // one section (a quick look; the files then hold only it)
  std::filesystem::create_directories(out);
  bench::OutputFile csv(out / "canvas_tradeoff.csv"), md(out / "canvas_tradeoff.md");
  bench::TradeoffPoints points(out / "canvas_tradeoff_points.csv");
  const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
  md << "# Dynamic canvas: temporal coherence, flatness, and error against run time\n\nDevice: "
     << context->description() << "\n\n";

  scene::Scene sc = scene::loadScene(std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/scenes/default.json");
  scene::AssetCache cache;
  const auto objects = cache.getAll(sc);

  // 1. Camera paths. 512 × 384 (the canvas costs seconds per frame at 1024² on llvmpipe).
  if (only.empty() || only == "coherence") {
    const int w = quick ? 128 : 512, h = quick ? 96 : 384;
    md << "## Temporal coherence and flatness, sample scene, " << w << "×" << h << "\n\n"
       << "Warping error: mean squared difference between frame t and frame t−1 warped to it (positions from the "
          "depth buffer, or the background dome; occluded and off-screen pixels left out), over the variance; mean "
          "over the path's consecutive pairs. 0 is perfect coherence; about 2 is none. Paths: orbit 1° per frame "
          "(6 frames), dolly 2× to 0.5× the distance (13 frames, ×2^(−1/6) each), pan 1 % of the scene's radius per "
          "frame (6 frames). Canvas defaults but `grain` 24 and `frequency` 0.06 (0.16 cycles per pixel here: the "
          "warp's bilinear sampling needs the pattern well below Nyquist, and a kernel narrow enough in frequency "
          "for the silk's spectrum to have a clear peak away from 0).\n\n";
    std::map<Kind, std::map<std::string, double>> errors;
    // Flatness is measured on the mean spectrum of `seeds` realisations per frame (the
    // scene seed draws the kernels): one periodogram of a broad spectrum such as the rice
    // paper's wanders by tens of per cent from seed to seed. The estimator's own spread is
    // measured too: the same view, `batches` disjoint sets of seeds.
    const int seeds = quick ? 2 : 8, batches = quick ? 3 : 8;
    std::map<Kind, std::vector<render::SpectrumPeak>> dolly_peaks, floor_peaks;
    std::vector<std::vector<Frame>> dolly_frames(std::size(kKinds));
    const char* paths[] = {"orbit", "dolly", "pan"};
    for (Kind kind : kKinds) {
      scene::Scene s = withKind(sc, kind);
      s.canvas.grain = 24;
      s.canvas.frequency = 0.06;
      render::InkRenderer r(s, objects);
      const render::OrbitCamera base =
          render::sceneCamera(s, r.worldBounds(), static_cast<double>(w) / h, render::frameKey(s, 0, 1, 0.0));
      const double radius = 0.5 * glm::length(r.worldBounds().size());
      for (const char* path : paths) {
        const std::string p = path;
        const int frames = quick ? (p == "dolly" ? 5 : 3) : p == "dolly" ? 13 : 6;
        const std::vector<render::OrbitCamera> cams = cameraPath(base, p, frames, r.worldBounds().centre(), radius);
        std::vector<Frame> frames_out;
        double sum = 0;
        for (std::size_t i = 0; i < cams.size(); ++i) {
          frames_out.push_back(renderFrame(r, kind, cams[i], w, h));
          if (i > 0) sum += render::warpingError(frames_out[i - 1].view, frames_out[i].view).relative();
          if (p == "dolly") {
            std::vector<image::Image> realisations{frames_out[i].view.values};
            for (int k = 1; k < seeds; ++k) realisations.push_back(seeded(r, s, s.seed + k, kind, cams[i], w, h));
            dolly_peaks[kind].push_back(render::spectrumPeak(realisations));
          }
        }
        if (p == "dolly") {
          for (int b = 0; b < batches; ++b) {
            std::vector<image::Image> realisations;
            for (int k = 0; k < seeds; ++k)
              realisations.push_back(seeded(r, s, s.seed + static_cast<std::uint64_t>(seeds * (b + 1) + k), kind,
                                            cams[cams.size() / 2], w, h));
            floor_peaks[kind].push_back(render::spectrumPeak(realisations));
          }
          std::fprintf(stderr, "%s dolly spectra: %d seeds a frame, %d batches\n", kKindNames[static_cast<int>(kind)],
                       seeds, batches);
        }
        errors[kind][p] = sum / static_cast<double>(cams.size() - 1);
        std::fprintf(stderr, "%s %s: %.4f\n", kKindNames[static_cast<int>(kind)], path, errors[kind][p]);
        if (p == "dolly") dolly_frames[static_cast<std::size_t>(kind)] = std::move(frames_out);
      }
    }
    md << "| canvas | orbit | dolly | pan | ÷ static (orbit, dolly, pan) |\n|---|---|---|---|---|\n";
    csv << "section,kind,path,warping_error,ratio_to_static\n";
    for (Kind kind : kKinds) {
      char line[512];
      std::snprintf(line, sizeof line, "| %s | %.4f | %.4f | %.4f | %.3f, %.3f, %.3f |\n",
                    kKindNames[static_cast<int>(kind)], errors[kind]["orbit"], errors[kind]["dolly"],
                    errors[kind]["pan"], errors[kind]["orbit"] / errors[Kind::Static]["orbit"],
                    errors[kind]["dolly"] / errors[Kind::Static]["dolly"],
                    errors[kind]["pan"] / errors[Kind::Static]["pan"]);
      md << line;
      for (const char* path : paths) {
        csv << "coherence," << kKindNames[static_cast<int>(kind)] << "," << path << "," << errors[kind][path] << ","
            << errors[kind][path] / errors[Kind::Static][path] << "\n";
      }
    }
    md << "\nFlatness through the dolly (0.5× to 2×), on the mean spectrum of " << seeds
       << " seeds a frame: the screen-space peak frequency (cycles per pixel) of the ring-averaged power (centroid "
          "of the rings above half its maximum) and of the radial energy (the same of the ring-summed power, the "
          "energy per unit |f|: a flat-topped low-pass spectrum such as the rice paper's has its ring-average "
          "maximum on the lowest, noisiest rings, while its energy peaks at the cut-off), the mean frequency "
          "(power-weighted over all rings) and the contrast (standard deviation); largest deviation from their "
          "means over the frames. Goal: within ±5 % and ±10 %. Beside each, the estimator's own spread: the "
          "largest deviation over "
       << batches << " disjoint sets of " << seeds
       << " seeds at one view (the middle of the dolly), where the true spectrum is the same for all; a goal "
          "tighter than it cannot be checked. The object-space texture is measured on the mountain only (the rest "
          "set to its mean).\n\n"
       << "| canvas | peak (ring average) | dolly | own | peak (energy) | dolly | own | mean frequency | dolly | own | "
          "contrast | dolly |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    csv << "section,kind,peak_frequency,peak_max_deviation,peak_estimator_spread,energy_peak_frequency,"
           "energy_peak_max_deviation,energy_peak_estimator_spread,mean_frequency,mean_max_deviation,"
           "mean_estimator_spread,contrast,contrast_max_deviation\n";
    // Mean and largest relative deviation of one measure over frames or seed sets.
    struct Spread {
      double mean = 0, deviation = 0;
    };
    auto spread = [](const std::vector<render::SpectrumPeak>& peaks, double render::SpectrumPeak::*measure) {
      Spread r;
      for (const auto& p : peaks) r.mean += p.*measure / static_cast<double>(peaks.size());
      for (const auto& p : peaks) r.deviation = std::max(r.deviation, std::abs(p.*measure / r.mean - 1));
      return r;
    };
    for (Kind kind : kKinds) {
      std::string row = std::string("| ") + kKindNames[static_cast<int>(kind)];
      csv << "flatness," << kKindNames[static_cast<int>(kind)];
      for (auto measure : {&render::SpectrumPeak::frequency, &render::SpectrumPeak::energy_frequency,
                           &render::SpectrumPeak::mean_frequency, &render::SpectrumPeak::contrast}) {
        const Spread d = spread(dolly_peaks[kind], measure), e = spread(floor_peaks[kind], measure);
        const bool contrast = measure == &render::SpectrumPeak::contrast;
        char cell[128];
        if (contrast) {
          std::snprintf(cell, sizeof cell, " | %.3f | %.1f %%", d.mean, 100 * d.deviation);
        } else {
          std::snprintf(cell, sizeof cell, " | %.4f | %.1f %% | %.1f %%", d.mean, 100 * d.deviation, 100 * e.deviation);
        }
        row += cell;
        csv << "," << d.mean << "," << d.deviation;
        if (!contrast) csv << "," << e.deviation;
      }
      md << row << " |\n";
      csv << "\n";
    }
    // Pictures: the dolly's first, middle and last frames, centre crops: the painted frame
    // with the dynamic silk and with the static one, the dynamic canvas alone, and the
    // object-space texture alone.
    const int cw = std::min(224, w), ch = std::min(168, h);
    image::Image mosaic(3 * cw, 5 * ch, 3);
    const int last = static_cast<int>(dolly_frames[0].size()) - 1;  // every kind has the same path
    const int picks[3] = {0, last / 2, last};
    for (int col = 0; col < 3; ++col) {
      const auto i = static_cast<std::size_t>(picks[col]);
      auto frame = [&](Kind kind) -> const Frame& { return dolly_frames[static_cast<std::size_t>(kind)][i]; };
      paste(mosaic, frame(Kind::TilesSilk).picture, col * cw, 0, cw, ch, false);
      paste(mosaic, frame(Kind::Static).picture, col * cw, ch, cw, ch, false);
      paste(mosaic, frame(Kind::TilesSilk).view.values, col * cw, 2 * ch, cw, ch, true);
      paste(mosaic, frame(Kind::Silk).view.values, col * cw, 3 * ch, cw, ch, true);
      paste(mosaic, frame(Kind::ObjectSpace).view.values, col * cw, 4 * ch, cw, ch, false);
    }
    image::saveImage(mosaic, out / "canvas_dolly.png");
    md << "\n![dolly](canvas_dolly.png)\n\nColumns: 2×, 1× and 0.5× the distance (centre crops). Rows: the painted "
          "frame on tiles silk (default contrast); on static silk; the tiles canvas alone; the splatted canvas "
          "alone; the object-space texture alone (its grain grows as the camera comes closer).\n\n";
  }

  // 2. N′: cost on the sample scene at 1024², error on a facing plane.
  if (only.empty() || only == "impulses") {
    md << "## N′: error against run time\n\n"
       << "Cost: the sample scene at 1024², silk canvas, canvas and G-buffer passes timed by GPU timestamps in the "
          "same frames (median of 3). Error: one-way silk (`mix` 0) on a plane of 128 triangles filling a 512² "
          "frame, `grain` 32 (16 px here), `frequency` 0.1 (0.05 cycles per pixel here): the triangles are large "
          "enough to hold several kernels each even at N′ = 8 (see render.md on fine meshes); relative L2 distance "
          "between the ring-averaged periodogram (Hann "
          "window, mean of 4 seeds) and the same average of the analytic Gabor spectrum, over rings above 1 % of "
          "its peak; the variance (1 expected); the excess kurtosis (0 for Gaussian noise, ~1/N′ for sparse "
          "convolution).\n\n"
       << "| N′ | canvas ms | G-buffer ms | canvas ÷ G-buffer | spectrum error | variance | excess kurtosis |\n"
          "|---|---|---|---|---|---|---|\n";
    csv << "section,impulses,canvas_ms,gbuffer_ms,ratio,spectrum_error,variance,excess_kurtosis\n";
    scene::Scene s = sc;
    s.canvas.type = scene::CanvasType::Silk;
    s.canvas.method = scene::CanvasMethod::Splat;
    render::InkRenderer r(s, objects);
    const render::OrbitCamera cam = render::sceneCamera(s, r.worldBounds(), 1.0, render::frameKey(s, 0, 1, 0.0));

    // The facing plane.
    // The plane keeps its size with --quick: its pattern is in pixels of a 1024-tall frame.
    const int n = 512, frame = quick ? 256 : 1024;
    scene::Scene ps = scene::parseScene(
        nlohmann::json{
            {"objects",
             nlohmann::json::array(
                 {{{"mesh", "memory.obj"}, {"lines", {{"enabled", false}}}, {"shading", {{"enabled", false}}}}})},
            {"camera", {{"elevation", 89.0}, {"azimuth", 0.0}, {"zoom", 1.6}}},
            {"canvas", {{"type", "silk"}, {"method", "splat"}, {"grain", 32}, {"frequency", 0.1}, {"mix", 0.0}}},
            {"output", {{"width", n}, {"height", n}, {"fade", 0.0}}}},
        "plane", ".");
    const mesh::Mesh plane = mesh::heightGrid(9, 9, 1.0 / 8, [](double, double) { return 0.0; });
    const std::vector<scene::LoadedObject> plane_objects{
        {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(plane, ps.objects[0])), nullptr}};

    for (double impulses : quick ? std::vector<double>{8, 32} : std::vector<double>{8, 16, 32, 64, 128}) {
      s.canvas.impulses = impulses;
      r.setScene(s);
      std::vector<double> canvas_ms, gbuffer_ms;
      for (int rep = 0; rep < 3; ++rep) {
        render::OrbitCamera c = cam;
        c.azimuth_deg += 0.01 * rep;
        render::FrameStats st;
        r.render(c, frame, frame, &st);
        for (const auto& p : st.passes) {
          if (p.name == "canvas") canvas_ms.push_back(p.gpu_ms);
          if (p.name == "gbuffer") gbuffer_ms.push_back(p.gpu_ms);
        }
      }
      // Error on the plane: ring-averaged periodograms over 4 seeds against the analytic one.
      ps.canvas.impulses = impulses;
      std::vector<double> measured(n / 2, 0.0), expected(n / 2, 0.0), count(n / 2, 0.0);
      double var = 0, kurt = 0;
      const int seeds = quick ? 2 : 4;
      noise::CanvasNoiseOptions o;
      for (int seed = 1; seed <= seeds; ++seed) {
        ps.seed = static_cast<std::uint64_t>(seed);
        render::InkRenderer pr(ps, plane_objects);
        pr.render(render::sceneCamera(ps, pr.worldBounds(), 1.0, {0, 89, 1.6}), n, n);
        const image::Image c = pr.passTarget("canvas")->colour(0).download(1);
        o = pr.canvas()->noiseOptions(n);
        double mean = 0;
        for (float v : c.pixels) mean += v / static_cast<double>(c.pixels.size());
        double v2 = 0;
        for (float v : c.pixels) v2 += (v - mean) * (v - mean) / static_cast<double>(c.pixels.size());
        var += v2 / seeds;
        kurt += excessKurtosis(c) / seeds;
        const std::vector<double> ring = render::radialPowerSpectrum(c);
        for (std::size_t b = 0; b < measured.size(); ++b) measured[b] += ring[b] / seeds;
      }
      // The analytic spectrum of the same Gabor noise (K = 1), over σ² of the canvas. The
      // image's rows run down, so its y axis is the scene's −y: ω0 = 0 is unaffected.
      noise::GaborOptions g;
      g.a = noise::canvasBandwidth(o);
      g.F0 = o.F0;
      g.omega0 = o.omega0;
      g.impulses = o.impulses;
      const noise::GaborNoise gabor(g);
      const double sigma = noise::canvasSigma(o);
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const double fx = (x <= n / 2 ? x : x - n) / static_cast<double>(n),
                       fy = (y <= n / 2 ? y : y - n) / static_cast<double>(n);
          const auto b = static_cast<std::size_t>(std::hypot(fx, fy) * n);
          if (b == 0 || b >= expected.size()) continue;
          expected[b] += gabor.spectrum(fx, fy) / (sigma * sigma);
          count[b] += 1;
        }
      double peak = 0, err2 = 0, ref2 = 0;
      for (std::size_t b = 1; b < expected.size(); ++b) peak = std::max(peak, expected[b] / std::max(count[b], 1.0));
      for (std::size_t b = 1; b < expected.size(); ++b) {
        const double e = expected[b] / std::max(count[b], 1.0), m = measured[b];
        if (e < 0.01 * peak) continue;
        err2 += (m - e) * (m - e);
        ref2 += e * e;
      }
      const double spectrum_error = std::sqrt(err2 / ref2);
      const double cm = median(canvas_ms), gm = median(gbuffer_ms);
      char line[512];
      std::snprintf(line, sizeof line, "| %.0f | %.0f | %.0f | %.1f | %.3f | %.3f | %.3f |\n", impulses, cm, gm,
                    cm / gm, spectrum_error, var, kurt);
      md << line;
      std::fputs(line, stderr);
      csv << "impulses," << impulses << "," << cm << "," << gm << "," << cm / gm << "," << spectrum_error << "," << var
          << "," << kurt << "\n";
      const std::string series = "silk canvas, N' 8 .. 128 (sample scene at " + std::to_string(frame) + "²)";
      points.add("canvas: spectrum against N'", "relative L2 error of the power spectrum", series, true, cm,
                 spectrum_error);
      points.add("canvas: Gaussianity against N'", "excess kurtosis (0 = Gaussian)", series, true, cm, kurt);
    }
  }

  // 3. The tiles canvas against the splatted one, and its patch knob.
  if (only.empty() || only == "tiles") tilesSection(md, csv, points, sc, objects, quick);
  // 4. Rice paper's mottle and its cell.
  if (only.empty() || only == "mottle") mottleSection(md, csv, points, sc, objects, quick);
  return 0;
}
