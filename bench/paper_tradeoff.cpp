// Error against run time for the paper-and-pigment passes' knobs (issue 25):
// - edge darkening's taps per side (edges.samples), on the light-colour sample scene, against
//   15 × 15 taps (the reference): mean and 99th-percentile |Δ| of the picture (0..255 levels)
//   over the frame, and the edges pass's GPU time;
// - the shadow map's resolution (shadow.resolution), on a box standing on a plane, against
//   the analytic shadow (the ray from each plane point towards the light meets the box or
//   not): the plane's pixels washed wrongly, as a share of the shadow's area, and the shadow
//   pass's GPU time when it draws its map.
// Writes paper_tradeoff.md, .csv and _points.csv (for shanshui-bench's plots). --quick:
// 256² frames, fewer repeats.
//   bench_paper_tradeoff [--out DIR] [--quick]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_args.h"
#include "bench_output.h"
#include "box_on_plane.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
using nlohmann::json;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double passMs(const render::FrameStats& st, const std::string& name) {
  for (const render::PassTime& p : st.passes)
    if (p.name == name) return p.gpu_ms;
  return std::nan("");
}

// A frame of `r` at a camera nudged by `nudge` degrees (so the renderer does not return the
// frame it cached), and the named pass's GPU time.
image::Image frame(render::InkRenderer& r, int size, double nudge, const std::string& pass, double* ms) {
  const scene::Camera& c = r.scene().camera;
  render::OrbitCamera cam = r.camera({c.azimuth_deg, c.elevation_deg, c.zoom}, 1.0);
  cam.azimuth_deg += nudge;
  render::FrameStats st;
  image::Image out = r.render(cam, size, size, &st, true).colour(0).download(3);
  if (ms) *ms = passMs(st, pass);
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(argc, argv, "bench_paper_tradeoff [--out DIR] [--quick]", {});
  std::filesystem::create_directories(args.out);
  const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
  const int size = args.quick ? 256 : 1024, repeats = args.quick ? 3 : 7;
  bench::OutputFile md(args.out / "paper_tradeoff.md"), csv(args.out / "paper_tradeoff.csv");
  bench::TradeoffPoints points(args.out / "paper_tradeoff_points.csv");
  csv << "knob,value,ms,error_mean,error_p99\n";
  char line[256];

  // Edge darkening: taps per side against 15 × 15.
  {
    scene::Scene s = scene::loadScene(std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/scenes/light_colour.json");
    if (args.quick) s.objects[0].max_vertices = 20000;
    scene::AssetCache cache;
    render::InkRenderer r(s, cache.getAll(s));
    s.edges.samples = 15;
    r.setScene(s);
    const image::Image reference = frame(r, size, 0.0, "edges", nullptr);
    md << "## Edge darkening: taps per side against 15 × 15\n\nThe light-colour sample at " << size << "², edges "
       << "radius " << s.edges.radius << " px at 1024 high. Error: |Δ| of the picture against 15 × 15 taps, in 0..255 "
       << "levels; time: the edges pass on the GPU (median of " << repeats << ").\n\n"
       << "| taps per side | taps | edges ms | mean |Δ| | p99 |Δ| |\n|---|---|---|---|---|\n";
    for (const int n : {1, 2, 3, 4, 5, 7, 9, 15}) {
      s.edges.samples = n;
      r.setScene(s);
      const image::Image out = frame(r, size, 0.0, "edges", nullptr);
      std::vector<double> ms;
      for (int k = 0; k < repeats; ++k) {
        double t = 0.0;
        frame(r, size, 1e-7 * (k + 1), "edges", &t);
        ms.push_back(t);
      }
      std::vector<double> diff;
      for (std::size_t i = 0; i < out.pixels.size(); ++i)
        diff.push_back(255.0 * std::abs(out.pixels[i] - reference.pixels[i]));
      double mean = 0.0;
      for (double d : diff) mean += d;
      mean /= static_cast<double>(diff.size());
      std::nth_element(diff.begin(), diff.begin() + static_cast<std::ptrdiff_t>(diff.size() * 99 / 100), diff.end());
      const double p99 = diff[diff.size() * 99 / 100], t = median(ms);
      std::snprintf(line, sizeof line, "| %d | %d | %.2f | %.3f | %.1f |\n", n, n * n, t, mean, p99);
      md << line;
      std::fprintf(stderr, "%s", line);
      csv << "edges_samples," << n << "," << t << "," << mean << "," << p99 << "\n";
      points.add("edge darkening: taps per side", "mean |difference| to 15 x 15 taps (0..255)", "1..15 per side", true,
                 t, mean);
    }
  }

  // Shadow map resolution against the analytic shadow of a box on a plane.
  {
    const test::BoxOnPlane box;
    const json j = box.scene(0.0);
    scene::Scene s = scene::parseScene(j, "box on a plane", ".");
    json off = j;
    off.erase("shadow");
    const scene::Scene s0 = scene::parseScene(off, "box on a plane", ".");
    const mesh::Mesh plane = mesh::heightGrid(81, 81, 0.05, [](double, double) { return 0.0; });
    auto loaded = [&](const scene::Scene& sc) { return test::BoxOnPlane::load(sc, plane); };
    render::InkRenderer r(s, loaded(s)), r0(s0, loaded(s0));
    const render::OrbitCamera cam = render::sceneCamera(s, r.worldBounds(), 1.0, {0, 89, 1.0});
    const image::Image bare = r0.render(cam, size, size).colour(0).download(3);
    md << "\n## Shadow map resolution against the analytic shadow\n\nA box (0.8 × 0.6 × 0.7) on a 4 × 4 plane, " << size
       << "² from above, unfiltered edge. Error: the plane's pixels washed where the box does not hide "
       << "them from the light, or not washed where it does, as a share of the shadow's area; time: the shadow "
       << "pass drawing its map.\n\n"
       << "| resolution | shadow ms | wrong pixels (% of the shadow) |\n|---|---|---|\n";
    for (const int res : {128, 256, 512, 1024, 2048, 4096}) {
      s.shadow.resolution = res;
      std::vector<double> ms;
      image::Image with, world;
      for (int k = 0; k < repeats; ++k) {
        s.light.direction = box.light * (1.0 + 1e-9 * (k + 1));  // a new light: the map is drawn again
        r.setScene(s);
        render::FrameStats st;
        with = r.render(cam, size, size, &st, true).colour(0).download(3);
        ms.push_back(passMs(st, "shadow"));
      }
      world = r.worldPositions();
      int shadowed = 0, wrong = 0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          if (world.at(x, y, 3) < 0.5) continue;
          const glm::dvec3 p(world.at(x, y, 0), world.at(x, y, 1), world.at(x, y, 2));
          if (!box.onPlaneBesideBox(p)) continue;
          const bool expected = box.hidden(p);
          const bool washed = std::abs(with.at(x, y, 0) - bare.at(x, y, 0)) > 0.05;
          shadowed += expected;
          wrong += washed != expected;
        }
      const double share = 100.0 * wrong / std::max(shadowed, 1), t = median(ms);
      std::snprintf(line, sizeof line, "| %d | %.2f | %.3f |\n", res, t, share);
      md << line;
      std::fprintf(stderr, "%s", line);
      csv << "shadow_resolution," << res << "," << t << "," << share << ",\n";
      points.add("shadow map: resolution", "pixels shadowed wrongly (% of the shadow)", "128..4096 texels", true, t,
                 share);
    }
  }
  std::fprintf(stderr, "wrote %s\n", (args.out / "paper_tradeoff.md").c_str());
  return 0;
}
