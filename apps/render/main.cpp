// shanshui-render: headless (EGL) ink-wash rendering of a scene to images and statistics.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/core/parse.h"
#include "shanshui/image/image_io.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/render/look_metrics.h"
#include "shanshui/scene/scene.h"
#include "tool_main.h"

namespace {

using namespace shanshui;

// out.png, frame 3 of 10 -> out_0003.png. A pattern with one %d or %0Nd (N <= 9) takes the
// frame number there; "%%" is a literal percent sign; any other % is refused (the name is
// never handed to printf).
std::filesystem::path framePath(const std::string& pattern, int index, int count) {
  if (pattern.find('%') != std::string::npos) {
    std::string name;
    int fields = 0;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
      if (pattern[i] != '%') {
        name += pattern[i];
        continue;
      }
      if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
        name += '%';
        ++i;
        continue;
      }
      std::size_t j = i + 1;
      const bool zero = j < pattern.size() && pattern[j] == '0';
      if (zero) ++j;
      int width = 0;
      if (j < pattern.size() && pattern[j] >= '1' && pattern[j] <= '9') width = pattern[j++] - '0';
      if (j >= pattern.size() || pattern[j] != 'd' || ++fields > 1) {
        throw makeError("-o ", pattern,
                        ": a frame pattern takes one %d or %0Nd (e.g. frame_%04d.png); '%' must be "
                        "written %%");
      }
      std::string number = std::to_string(index);
      if (static_cast<int>(number.size()) < width) number.insert(0, width - number.size(), zero ? '0' : ' ');
      name += number;
      i = j;
    }
    if (count > 1 && fields == 0) {
      const std::filesystem::path p(name);
      return p.parent_path() / (p.stem().string() + "_" + std::to_string(index) + p.extension().string());
    }
    return name;
  }
  if (count <= 1) return pattern;
  const std::filesystem::path p(pattern);
  char suffix[32];
  std::snprintf(suffix, sizeof suffix, "_%04d", index);
  return p.parent_path() / (p.stem().string() + suffix + p.extension().string());
}

// The scene (or lone mesh or DEM) with the --set overrides and, when given, --size WxH; a lone
// input's file, read for its proportions, is handed to `cache`.
scene::Scene loadSized(const std::string& input, std::vector<std::string> sets, const std::string& size,
                       scene::AssetCache& cache) {
  if (size.size()) {
    const Size2 s = parseSize(size, "--size");
    // The scene's output.width and output.height range, said of the option that gave it.
    constexpr int kMaxSide = 16384;
    if (s.width > kMaxSide || s.height > kMaxSide) {
      throw makeError("--size: '", size, "' is out of range; expected each side in [1, ", kMaxSide, "]");
    }
    sets.push_back("output.width=" + std::to_string(s.width));
    sets.push_back("output.height=" + std::to_string(s.height));
  }
  std::vector<std::string> notes;
  scene::Scene s = scene::loadSceneInput(input, sets, &notes, &cache);
  // What a lone DEM or piece of land was given from its proportions (painted as land, raised,
  // a sea, trees), so it can be undone.
  for (const std::string& n : notes)
    std::fprintf(stderr, "shanshui-render: note: %s: %s; --set changes it\n", input.c_str(), n.c_str());
  return s;
}

// --benchmark: frames back to back with the camera turning (no frame is a cache hit), timed
// per pass on the GPU, nothing read back or encoded between them; the first two seconds warm
// the GPU up and are not counted. Frames stay in flight: at most kFramesInFlight are queued
// ahead of the GPU (fences), and each frame's timer queries are read when the GPU has
// reached them, a frame or two later, so the CPU never waits for a frame it just submitted
// and the GPU never idles between frames.
constexpr std::size_t kFramesInFlight = 2;

void runBenchmark(const std::string& input, std::vector<std::string> sets, const std::string& size, int count,
                  const std::string& stats_path) {
  scene::AssetCache cache;
  const scene::Scene sc = loadSized(input, std::move(sets), size, cache);
  OutputSet outputs({input});
  if (!stats_path.empty()) outputs.declare(stats_path, "--stats", {".json"});
  const auto objects = cache.getAll(sc);
  const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
  render::InkRenderer renderer(sc, objects);
  renderer.setLateTiming(true);
  const int w = sc.output.pixelWidth(), h = sc.output.pixelHeight();
  const scene::CameraKey start = render::frameKey(sc, 0, 1, 0.0);
  std::map<std::string, std::vector<double>> passes, submit;
  std::vector<double> frame_ms, gpu_ms, submit_ms, camera_ms, uniforms;
  std::deque<GLsync> fences;
  std::deque<bool> timed;  // per frame whose times are not read yet: whether they count
  auto readTimes = [&](bool wait) {
    while (!timed.empty()) {
      const std::optional<std::vector<render::PassTime>> t = renderer.lateTimes(wait);
      if (!t) return;
      const bool counts = timed.front();
      timed.pop_front();
      if (!counts) continue;
      double sum = 0.0;
      for (const render::PassTime& p : *t) {
        passes[p.name].push_back(p.gpu_ms);
        sum += p.gpu_ms;
      }
      gpu_ms.push_back(sum);
    }
  };
  auto waitOldest = [&] {
    glClientWaitSync(fences.front(), GL_SYNC_FLUSH_COMMANDS_BIT, 60'000'000'000ull);
    glDeleteSync(fences.front());
    fences.pop_front();
  };
  using Clock = std::chrono::steady_clock;
  auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  const auto warm_until = Clock::now() + std::chrono::seconds(2);
  Clock::time_point previous = Clock::now(), first{};
  // The process's CPU time over the counted frames, all threads: a measure of work that a
  // busy machine does not stretch (llvmpipe's rasteriser threads are this process's).
  auto cpuSeconds = [] {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  double cpu_start = 0.0, previous_cpu = cpuSeconds();
  for (int i = 0, counted = 0; counted < count; ++i) {
    const bool counts = Clock::now() >= warm_until;
    scene::CameraKey key = start;
    key.azimuth_deg += 0.25 * i;
    render::FrameStats fs;
    // The camera (its framing) apart from render(): the drawn framing looks at every drawn
    // point of the scene.
    const auto t_camera = Clock::now();
    const render::OrbitCamera camera = renderer.camera(key, static_cast<double>(w) / h);
    const auto t0 = Clock::now();
    renderer.render(camera, w, h, &fs, true, i / 60.0);
    const double submitted = ms(Clock::now() - t0);
    fences.push_back(glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0));
    glFlush();
    timed.push_back(counts);
    if (fences.size() > kFramesInFlight) waitOldest();
    readTimes(false);
    const auto now = Clock::now();
    if (counts) {
      if (counted++ == 0) {
        first = previous;
        cpu_start = previous_cpu;
      }
      frame_ms.push_back(ms(now - previous));
      submit_ms.push_back(submitted);
      camera_ms.push_back(ms(t0 - t_camera));
      uniforms.push_back(static_cast<double>(fs.uniforms_set));
      for (const auto& p : fs.submit) submit[p.name].push_back(p.cpu_ms);
    }
    previous = now;
    previous_cpu = cpuSeconds();
  }
  while (!fences.empty()) waitOldest();
  readTimes(true);
  const double frame_cpu_ms = 1000.0 * (cpuSeconds() - cpu_start) / count;
  const double fps = 1000.0 * static_cast<double>(count) / std::max(ms(Clock::now() - first), 1e-9);
  auto quantile = [](std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
  };
  nlohmann::json out = {{"scene", input},
                        {"device", context->description()},
                        {"size", {w, h}},
                        {"frames", count},
                        {"passes_built", renderer.passesBuilt()},
                        {"elements", nlohmann::json::array()},
                        {"frames_in_flight", kFramesInFlight},
                        {"fps", fps},
                        {"frame_wall_ms", {{"median", quantile(frame_ms, 0.5)}, {"p90", quantile(frame_ms, 0.9)}}},
                        {"submit_cpu_ms", {{"median", quantile(submit_ms, 0.5)}, {"p90", quantile(submit_ms, 0.9)}}},
                        {"camera_cpu_ms", {{"median", quantile(camera_ms, 0.5)}, {"p90", quantile(camera_ms, 0.9)}}},
                        {"uniforms_set_per_frame", quantile(uniforms, 0.5)},
                        {"frame_cpu_ms", frame_cpu_ms},
                        {"passes_gpu_ms", {{"median", quantile(gpu_ms, 0.5)}, {"p90", quantile(gpu_ms, 0.9)}}},
                        {"pass_gpu_ms", nlohmann::json::object()}};
  for (const auto& o : objects)
    out["elements"].push_back({{"count", o.elements ? o.elements->instances.size() : 0},
                               {"place_seconds", o.elements ? o.elements->place_seconds : 0.0}});
  std::printf("%s\n%s, %dx%d, %d frames after 2 s of warm-up\n", context->description().c_str(), input.c_str(), w, h,
              count);
  for (const auto& [name, v] : passes) {
    out["pass_gpu_ms"][name] = {{"median", quantile(v, 0.5)}, {"p90", quantile(v, 0.9)}};
    std::printf("  %-18s GPU median %8.3f ms  p90 %8.3f ms\n", name.c_str(), quantile(v, 0.5), quantile(v, 0.9));
  }
  std::printf("  %-18s GPU median %8.3f ms  p90 %8.3f ms\n", "passes", quantile(gpu_ms, 0.5), quantile(gpu_ms, 0.9));
  out["pass_cpu_ms"] = nlohmann::json::object();
  for (const auto& [name, v] : submit) {  // each pass's run() on the CPU: submission and any wait
    out["pass_cpu_ms"][name] = {{"median", quantile(v, 0.5)}, {"p90", quantile(v, 0.9)}};
    std::printf("  %-18s CPU median %8.3f ms  p90 %8.3f ms\n", name.c_str(), quantile(v, 0.5), quantile(v, 0.9));
  }
  std::printf("  %-18s CPU median %8.3f ms  p90 %8.3f ms (render(): submission, no wait)\n", "submit",
              quantile(submit_ms, 0.5), quantile(submit_ms, 0.9));
  std::printf("  %-18s CPU median %8.3f ms  p90 %8.3f ms (the view's camera and framing)\n", "camera",
              quantile(camera_ms, 0.5), quantile(camera_ms, 0.9));
  std::printf("  %-18s wall median %7.3f ms  p90 %8.3f ms (%.0f fps, %zu frames in flight)\n", "frame",
              quantile(frame_ms, 0.5), quantile(frame_ms, 0.9), fps, kFramesInFlight);
  std::printf("  %-18s CPU   mean %8.3f ms (the process, every thread)\n", "frame", frame_cpu_ms);
  std::printf("  %-18s %.0f a frame sent to the driver (not: the frame's block, values a program holds)\n",
              "uniforms set", quantile(uniforms, 0.5));
  if (!stats_path.empty()) outputs.stage(stats_path, tools::jsonText(out, stats_path));
  outputs.commit();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Renders a scene (or a single mesh or DEM in the sample's style: land is raised when flat, its sea "
      "becomes water and, when small, it grows trees; each choice is printed with the key that undoes it) "
      "headless, with EGL: no display needed.",
      "shanshui-render"};
  app.footer(
      "Examples:\n"
      "  shanshui-render samples/scenes/default.json -o out/mountain.png\n"
      "  shanshui-render samples/scenes/default.json -o out/orbit.png --frames 36 --orbit 360 --stats out/stats.json\n"
      "  shanshui-render samples/scenes/default.json -o out/a.png --set objects.0.lines.curve_factor=2 "
      "--set canvas.type=none\n"
      "  shanshui-render out/mountain.obj -o out/mountain.png --size 1280x800\n"
      "  shanshui-render N46E007.hgt -o alps.png --set water.enabled=false\n"
      "  shanshui-render --describe            # every scene key: default, range, meaning (Markdown)\n"
      "Scene keys: docs/scene.md.");
  std::string input, output, size, stats_path;
  std::vector<std::string> sets;
  int frames = 1, benchmark = 0;
  double orbit = 360.0, fps = 24.0;
  std::string describe_into;
  bool verbose = false, smallest = false, describe = false;
  app.add_option("scene", input,
                 "scene (.json), or a mesh (.obj .gltf .glb .fbx .stl ...) or DEM (.dem .asc .tif .hgt .img ...) "
                 "to render alone");
  app.add_option("-o,--output", output, "image to write (.png .jpg .tif .exr); numbered with --frames");
  app.add_flag("--describe", describe, "print every scene key with its default, range and meaning (Markdown) and exit");
  app.add_option("--describe-into", describe_into,
                 "rewrite the key tables of a Markdown file (between '<!-- keys: GROUP -->' and '<!-- /keys -->') "
                 "from the description, e.g. docs/scene.md, and exit");
  app.add_option("--size", size, "output size WxH (default: the scene's output.width x output.height)");
  app.add_option("--frames", frames, "render N frames along camera.path, or an orbit without one")->default_val(1);
  app.add_option("--orbit", orbit, "degrees turned around +Z over the frames (no camera.path)")->default_val(360.0);
  app.add_option("--fps", fps, "frames per second of a sequence: frame i is at time i / fps (spinning objects)")
      ->default_val(24.0);
  app.add_option("--benchmark", benchmark,
                 "time N frames back to back (camera turning a quarter degree a frame, no readback or encoding), "
                 "after two seconds of warm-up: per pass GPU median and 90th percentile, frame wall time; no -o "
                 "needed")
      ->default_val(0);
  app.add_option("--set", sets, "override a scene key, dotted path = JSON value (repeatable)");
  app.add_option("--stats", stats_path, "write JSON statistics: passes built, per frame time and pass GPU times");
  app.add_flag("--smallest", smallest, "compress PNG/TIFF/EXR output hardest (slower); default: fast compression");
  app.add_flag("-v,--verbose", verbose, "print the GL platform and load times");
  return tools::runBatchableTool(app, argc, argv, [&] {
    if (describe) {
      std::fputs(scene::describeMarkdown().c_str(), stdout);
      return;
    }
    if (!describe_into.empty()) {
      const std::string doc = readInputFile(describe_into, "a Markdown page", kMaxTextInputBytes);
      const std::string updated = scene::spliceDescription(doc, describe_into);
      if (updated != doc) writeFileAtomically(describe_into, updated);
      std::fprintf(stderr, "%s: %s\n", describe_into.c_str(), updated == doc ? "up to date" : "tables rewritten");
      return;
    }
    if (input.empty()) throw makeError("scene: required (a scene, mesh or DEM file; see --help)");
    if (benchmark < 0 || benchmark > 1000000)
      throw makeError("--benchmark: ", benchmark, " is out of range; expected [0, 1000000]");
    if (benchmark > 0) {
      runBenchmark(input, sets, size, benchmark, stats_path);
      return;
    }
    if (output.empty()) throw makeError("-o: required (the image to write; see --help)");
    if (frames < 1 || frames > 100000) throw makeError("--frames: ", frames, " is out of range; expected [1, 100000]");
    if (!std::isfinite(orbit)) throw makeError("--orbit: must be finite");
    if (!(fps > 0 && fps <= 1e4)) throw makeError("--fps: ", fps, " is out of range; expected (0, 10000]");
    scene::AssetCache cache;
    const scene::Scene sc = loadSized(input, sets, size, cache);
    OutputSet outputs({input});
    for (int i = 0; i < frames; ++i)
      outputs.declare(framePath(output, i, frames), "-o", image::writableImageExtensions());
    if (!stats_path.empty()) outputs.declare(stats_path, "--stats", {".json"});

    const auto objects = cache.getAll(sc);
    const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
    if (verbose) std::fprintf(stderr, "%s\n", context->description().c_str());
    render::InkRenderer renderer(sc, objects);

    nlohmann::json stats;
    stats["scene"] = input;
    stats["device"] = context->description();
    stats["size"] = {sc.output.pixelWidth(), sc.output.pixelHeight()};
    stats["triangles"] = renderer.triangleCount();
    stats["passes_built"] = renderer.passesBuilt();
    stats["variants"] = renderer.variants();
    stats["load_seconds"] = nlohmann::json::array();
    for (const auto& o : objects) stats["load_seconds"].push_back(o.geometry->load_seconds);
    stats["place_seconds"] = nlohmann::json::array();  // trees and moss dots, per object
    for (const auto& o : objects) stats["place_seconds"].push_back(o.elements ? o.elements->place_seconds : 0.0);
    stats["grounded"] = nlohmann::json::array();  // where objects standing on others came to rest
    for (std::size_t i = 0; i < sc.objects.size(); ++i) {
      if (!sc.objects[i].grounded()) continue;
      const glm::dvec3 at(renderer.worldMatrix(i) * glm::dvec4(objects[i].geometry->bounds.centre(), 1.0));
      stats["grounded"].push_back({{"object", i}, {"on", sc.objects[i].ground.on}, {"centre", {at.x, at.y, at.z}}});
      if (verbose)
        std::fprintf(stderr, "objects.%zu '%s' stands on '%s', its centre at (%.1f, %.1f, %.1f)\n", i,
                     sc.objects[i].name.c_str(), sc.objects[i].ground.on.c_str(), at.x, at.y, at.z);
    }
    stats["frames"] = nlohmann::json::array();
    bool warned_dropped = false;
    for (int i = 0; i < frames; ++i) {
      render::FrameStats fs;
      const double time = i / fps;
      // Motion blur's velocities: the camera where it was one blur interval earlier.
      const scene::CameraKey previous = render::frameKey(sc, i - sc.motion_blur.interval * fps, frames, orbit);
      const image::Image img = renderer.renderImage(render::frameKey(sc, i, frames, orbit), &fs, time,
                                                    sc.motion_blur.enabled && frames > 1 ? &previous : nullptr);
      const std::filesystem::path path = framePath(output, i, frames);
      outputs.stage(path, image::encodeImage(img, path, image::PixelDepth::UInt8, {.smallest = smallest}));
      nlohmann::json f = {
          {"index", i},          {"time", time},         {"file", path.string()}, {"frame_ms", fs.frame_ms},
          {"cached", fs.cached}, {"redrawn", fs.redrawn}};
      f["passes"] = nlohmann::json::object();
      for (const auto& p : fs.passes) f["passes"][p.name] = p.gpu_ms;
      // A frame that made more tree and dot marks than it has room for leaves some out, and
      // not always the same ones: said, not silent.
      if (const std::size_t dropped = renderer.marksDropped(); dropped > 0) {
        f["marks_dropped"] = dropped;
        if (!warned_dropped)
          std::fprintf(
              stderr,
              "shanshui-render: warning: %s: %zu tree and dot marks had no room in the frame and were left out "
              "(which ones can change from run to run); lower the objects' trees.density or "
              "dots.density, or give fewer objects trees\n",
              path.string().c_str(), dropped);
        warned_dropped = true;
      }
      if (!stats_path.empty()) {  // what a painter would look at (docs/render.md), on the scene's surfaces
        image::Image subject(img.width, img.height, 1);
        const image::Image positions = renderer.worldPositions();
        for (std::size_t k = 0; k < subject.pixels.size(); ++k) subject.pixels[k] = positions.pixels[4 * k + 3];
        const render::LookStatistics look = render::lookStatistics(img, sc.output.paper, &subject);
        f["look"] = {{"paper_share", look.paper_share},           {"dark_share", look.dark_share},
                     {"dark_width_px", look.dark_width_px},       {"far_near_ink", look.far_near_ink},
                     {"longest_straight", look.longest_straight}, {"marks_per_mp", look.marks_per_mp},
                     {"mark_size_spread", look.mark_size_spread}};
      }
      stats["frames"].push_back(f);
      if (frames > 1) std::fprintf(stderr, "\rframe %d/%d", i + 1, frames);
      std::printf("%s\n", path.string().c_str());
    }
    if (frames > 1) std::fprintf(stderr, "\n");
    if (!stats_path.empty()) outputs.stage(stats_path, tools::jsonText(stats, stats_path));
    outputs.commit();
  });
}
