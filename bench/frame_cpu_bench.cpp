// The renderer's own CPU work per frame, apart from the driver's (issue 47 item 3). A frame
// the renderer has just drawn costs only its request: the size, the camera and a counter
// compared with the last frame's. Before, the request was text built every frame: the
// camera formatted into a string and the scene's parameter hash (a walk over every key of
// every object), copied into each pass's inputs. Both measured side by side in one run, on
// the default sample (one object) and the painting (ten), real time. And Program::set on a
// value the program already holds (nothing goes to the driver) against a value that
// changes every call (one driver call each).
//   build/bin/bench_frame_cpu
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>

#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace {

using namespace shanshui;

std::filesystem::path sample(const char* name) {
  return std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/scenes" / (std::string(name) + ".json");
}

render::GlContext& context() {
  static const auto c = render::GlContext::create({.kind = render::ContextKind::Headless});
  return *c;
}

// A cached frame: render() with the camera and size of the frame before.
void BM_CachedFrame(benchmark::State& state, const char* name) {
  context();
  const scene::Scene s = scene::loadScene(sample(name), {"output.width=128", "output.height=128"});
  scene::AssetCache cache;
  render::InkRenderer r(s, cache.getAll(s));
  const render::OrbitCamera cam = r.camera({-30, 30, 1.0}, 1.0);
  r.render(cam, 128, 128);
  render::FrameStats stats;
  for (auto _ : state) {
    r.render(cam, 128, 128, &stats);
    if (!stats.cached) state.SkipWithError("the frame was drawn again");
  }
}

// The request as it was built before, every frame.
void BM_RequestAsText(benchmark::State& state, const char* name) {
  const scene::Scene s = scene::loadScene(sample(name));
  render::OrbitCamera c;
  c.distance = 3.0;
  for (auto _ : state) {
    std::ostringstream k;
    k.precision(17);
    k << 128 << "x" << 128 << "|" << c.target.x << "," << c.target.y << "," << c.target.z << "," << c.distance << ","
      << c.azimuth_deg << "," << c.elevation_deg << "," << c.fov_y_deg << "," << c.near_plane << "," << c.far_plane
      << "|" << scene::parameterHash(s);
    std::string key = k.str();
    benchmark::DoNotOptimize(key);
  }
}

// Two uniforms of the ink pass's program set by name, a float and a vec3: the same values
// every time, or values that alternate.
void BM_SetUniforms(benchmark::State& state, bool alternate) {
  context();
  const render::Program p({"fullscreen.vert", "ink.frag"}, {"LINES", "SHADING", "CANVAS", "ELEMENTS", "SINGLE_OBJECT"});
  float v = 0.25f;
  for (auto _ : state) {
    if (alternate) v = v == 0.25f ? 0.5f : 0.25f;
    p.set("u_canvas_contrast", v);
    p.set("u_element_colour", glm::vec3(v, 0.2f, 0.3f));
  }
}

BENCHMARK_CAPTURE(BM_SetUniforms, values_kept, false)->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_SetUniforms, values_sent, true)->Unit(benchmark::kNanosecond);
BENCHMARK_CAPTURE(BM_CachedFrame, default_sample, "default")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_RequestAsText, default_sample, "default")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_CachedFrame, painting, "painting")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_RequestAsText, painting, "painting")->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
