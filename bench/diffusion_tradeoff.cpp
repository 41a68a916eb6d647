// Error against run time for the ink diffusion (SPEC.md sections 9 and 12), on the sample
// scene's own picture:
//  1. the main region by distance transform against the ring-by-ring iteration (CPU), for d;
//  2. boundary diffusion for n against a converged reference (n = 1000, CPU, double), CPU
//     and GPU times;
//  3. the full frame at 1024² with n = 5, d = 8 against the same frame without diffusion,
//     interleaved in one run (target ≤ 1.5x).
// Writes diffusion_tradeoff.md, .csv and _points.csv (for shanshui-bench's plots). --quick:
// quarter sizes and short sweeps.   bench_diffusion_tradeoff [--out DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_output.h"
#include "order_stats.h"
#include "shanshui/ink/diffusion.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_diffusion_pass.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
using bench::median;
using bench::quartiles;
using Clock = std::chrono::steady_clock;

double ms(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct Diff {
  double max = 0, mean = 0;
};

Diff difference(const std::vector<double>& a, const std::vector<double>& b) {
  Diff d;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double e = std::abs(a[i] - b[i]);
    d.max = std::max(d.max, e);
    d.mean += e;
  }
  d.mean /= static_cast<double>(a.size());
  return d;
}

// The sample scene rendered at size², its ink, and the GPU pass's inputs.
struct Input {
  image::Image picture;
  ink::InkField ink;
  render::Texture2D colour, absorbency;
};

Input renderInput(scene::Scene sc, const std::vector<scene::LoadedObject>& objects, int size, const double paper[3]) {
  sc.output.width = sc.output.height = size;
  render::InkRenderer r(sc, objects);
  Input in;
  in.picture = r.renderImage(render::frameKey(sc, 0, 1, 0.0));
  in.ink = ink::inkFromImage(in.picture, paper);
  in.colour = render::Texture2D::fromImage(in.picture, GL_RGBA8);
  in.absorbency = render::Texture2D::fromImage(image::Image(1, 1, 1, 1.0f), GL_R8);
  return in;
}

// Median GPU milliseconds of the pass over five runs.
double gpuMs(render::InkDiffusionPass& pass, const Input& in, const ink::DiffusionOptions& o, const double paper[3]) {
  std::vector<double> t;
  for (int rep = 0; rep < 5; ++rep) {
    render::GpuTimer timer;
    pass.run(in.colour, in.absorbency, o, glm::vec3(paper[0], paper[1], paper[2]), &timer);
    t.push_back(timer.collect().front().gpu_ms);
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(argc, argv, "bench_diffusion_tradeoff [--out DIR] [--quick]");
  const std::filesystem::path out = args.out;
  const bool quick = args.quick;
  const int mainSize = quick ? 128 : 512, boundarySize = quick ? 64 : 256, frameSize = quick ? 256 : 1024;
  std::filesystem::create_directories(out);
  bench::OutputFile csv(out / "diffusion_tradeoff.csv"), md(out / "diffusion_tradeoff.md");
  bench::TradeoffPoints points(out / "diffusion_tradeoff_points.csv");
  const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
  md << "# Ink diffusion: error against run time, and cost\n\nDevice: " << context->description()
     << "\n\nInput: the sample scene rendered without diffusion (lines, shading, wrinkles).\n\n";

  const scene::Scene shipped =
      scene::loadScene(std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/scenes/default.json");
  scene::Scene sc = shipped;
  sc.canvas.type = scene::CanvasType::None;  // the input of sections 1 and 2: lines, shading, wrinkles
  scene::AssetCache cache;
  const auto objects = cache.getAll(sc);
  const double paper[3] = {sc.output.paper.x, sc.output.paper.y, sc.output.paper.z};

  // 1. Main region: distance transform against the iteration, 512².
  {
    const Input input = renderInput(sc, objects, mainSize, paper);
    const ink::InkField& in = input.ink;
    render::InkDiffusionPass pass;
    md << "## Main region: distance transform against the ring-by-ring iteration, " << mainSize << "²\n\n"
       << "CPU: the two reference implementations; GPU: the compute pass with n = 0 (the transform alone, "
          "median of 5), its ink against the CPU iteration.\n\n"
       << "| d | CPU iteration ms | CPU distance transform ms | same rings | max ink difference | GPU ms | GPU max "
          "difference to the iteration |\n|---|---|---|---|---|---|---|\n";
    csv << "section,d,iteration_ms,distance_ms,same_rings,max_difference,gpu_ms,gpu_max_difference\n";
    for (int d : quick ? std::vector<int>{1, 8, 64} : std::vector<int>{1, 4, 8, 16, 64, 256}) {
      ink::DiffusionOptions o;
      o.ring_steps = d;
      std::vector<int> ra, rb;
      auto t = Clock::now();
      const ink::InkField a = ink::mainDiffusionIterative(in, o, &ra);
      const double ta = ms(t);
      t = Clock::now();
      const ink::InkField b = ink::mainDiffusionDistance(in, o, &rb);
      const double tb = ms(t);
      const Diff diff = difference(a.ink, b.ink);
      o.iterations = 0;
      const double gpu_ms = gpuMs(pass, input, o, paper);
      const image::Image gpu = pass.inkAfter();
      const Diff gdiff = difference(std::vector<double>(gpu.pixels.begin(), gpu.pixels.end()), a.ink);
      char line[256];
      std::snprintf(line, sizeof line, "| %d | %.1f | %.1f | %s | %.2e | %.1f | %.2e |\n", d, ta, tb,
                    ra == rb ? "yes" : "NO", diff.max, gpu_ms, gdiff.max);
      md << line;
      std::fputs(line, stderr);
      csv << "main," << d << "," << ta << "," << tb << "," << (ra == rb) << "," << diff.max << "," << gpu_ms << ","
          << gdiff.max << "\n";
      const char* plot = "diffusion main region against the ring iteration";
      const char* y = "max |ink difference| to the ring-by-ring iteration";
      points.add(plot, y, "ring iteration (CPU, the reference)", true, ta, 0.0);
      points.add(plot, y, "distance transform (CPU)", true, tb, diff.max);
      points.add(plot, y, "distance transform (GPU)", true, gpu_ms, gdiff.max);
    }
  }

  // 2. Boundary diffusion against n = 1000, 256².
  {
    const Input input = renderInput(sc, objects, boundarySize, paper);
    const ink::InkField& in = input.ink;
    render::InkDiffusionPass pass;
    ink::DiffusionOptions o;
    o.iterations = 1000;
    const ink::InkField reference = ink::diffuseInk(in, {}, o);
    md << "\n## Boundary diffusion: n against a converged reference (n = 1000, CPU double), " << boundarySize << "²\n\n"
       << "I_p is spread over the n iterations, so the result converges as n grows. Mean and max |ink "
          "difference| per pixel; CPU = the reference implementation, GPU = the compute pass (median of 5).\n\n"
       << "| n | mean error | max error | CPU ms | GPU ms |\n|---|---|---|---|---|\n";
    csv << "section,n,mean_error,max_error,cpu_ms,gpu_ms\n";
    for (int n : quick ? std::vector<int>{1, 5, 20} : std::vector<int>{1, 2, 5, 10, 20, 50, 100}) {
      o.iterations = n;
      auto t = Clock::now();
      const ink::InkField cpu = ink::diffuseInk(in, {}, o);
      const double tc = ms(t);
      const double gpu_ms = gpuMs(pass, input, o, paper);
      const Diff diff = difference(cpu.ink, reference.ink);
      char line[256];
      std::snprintf(line, sizeof line, "| %d | %.2e | %.2e | %.1f | %.2f |\n", n, diff.mean, diff.max, tc, gpu_ms);
      md << line;
      std::fputs(line, stderr);
      csv << "boundary," << n << "," << diff.mean << "," << diff.max << "," << tc << "," << gpu_ms << "\n";
      const char* plot = "boundary diffusion against n = 1000";
      const char* y = "mean |ink difference| to the converged result";
      points.add(plot, y, "CPU reference", true, tc, diff.mean);
      points.add(plot, y, "GPU pass", true, gpu_ms, diff.mean);
    }
  }

  // 3. The frame with and without diffusion, interleaved: the sample scene as shipped (its
  // rice-paper canvas included) and without the canvas (lines, shading, wrinkles only).
  const int rounds = quick ? 3 : 15;
  md << "\n## Frame cost at " << frameSize << "², sample scene, " << rounds
     << " interleaved rounds\n\nEach round times the frame without diffusion, then with it, each after an untimed "
        "frame of the same renderer (as in an animation); the ratio is taken per round (the shared machine's speed "
        "drifts between rounds) and its median and quartiles reported.\n\n"
        "| frame | without diffusion ms | with n = 5, d = 8 ms | ratio: median of rounds | quartiles | diffusion "
        "pass ms |\n|---|---|---|---|---|---|\n";
  csv << "section,frame,without_ms,with_n5_d8_ms,ratio,diffusion_ms\n";
  for (const auto& [name, base] : {std::pair<const char*, const scene::Scene&>{"the sample scene as shipped", shipped},
                                   std::pair<const char*, const scene::Scene&>{"without its canvas", sc}}) {
    scene::Scene with = base, without = base;
    with.output.width = with.output.height = without.output.width = without.output.height = frameSize;
    without.diffusion.ring_steps = 0;
    without.diffusion.iterations = 0;
    with.diffusion.ring_steps = 8;
    with.diffusion.iterations = 5;
    render::InkRenderer a(without, objects), b(with, objects);
    const render::OrbitCamera cam = render::sceneCamera(with, a.worldBounds(), 1.0, render::frameKey(with, 0, 1, 0.0));
    std::vector<double> ta, tb, ratio, diffusion_ms;
    // A frame of `r` timed after an untimed one of the same view (moved a hair, so it is
    // not the cached frame).
    auto timed = [&](render::InkRenderer& r, render::OrbitCamera c, render::FrameStats& st) {
      r.render(c, frameSize, frameSize);
      c.azimuth_deg += 1e-5;
      r.render(c, frameSize, frameSize, &st);
      return st.frame_ms;
    };
    for (int rep = 0; rep < rounds; ++rep) {
      render::OrbitCamera c = cam;
      c.azimuth_deg += 0.01 * rep;
      render::FrameStats st;
      ta.push_back(timed(a, c, st));
      tb.push_back(timed(b, c, st));
      ratio.push_back(tb.back() / ta.back());
      for (const auto& p : st.passes)
        if (p.name == "diffusion") diffusion_ms.push_back(p.gpu_ms);
    }
    const auto q = quartiles(ratio);
    const double x = median(ta), y = median(tb), r = q[1];
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %.1f | %.1f | %.2f | %.2f-%.2f | %.1f |\n", name, x, y, r, q[0], q[2],
                  median(diffusion_ms));
    md << line;
    std::fputs(line, stderr);
    csv << "frame," << name << "," << x << "," << y << "," << r << "," << median(diffusion_ms) << "\n";
  }
  md << "\nDiffusion pass: GPU timestamps. Seed 001 Table 2: 82-102 fps without, 3-11 fps with n = 5 (the diffusion "
        "costs ~10x the rest of the frame).\n";
  return 0;
}
