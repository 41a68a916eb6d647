// Error against run time for the ink renderer (SPEC.md sections 6, 7, 12), and its cost
// against a plain Lambert render, side by side in one run:
//  1. curvature per pixel from the two estimators (object-space per vertex, interpolated;
//     screen-space |fwidth(N)|/|fwidth(P)|) against the analytic value on a sphere (regular
//     and jittered), a torus and a paraboloid at three mesh resolutions;
//  2. the Gaussian CDF of the smoothed tone steps: the GLSL formula and a cheaper candidate
//     against std::erf;
//  3. lines + shading of the sample scene against a Lambert render of the same mesh;
//  4. the wrinkle texture's filters on the sample scene: picture against trilinear, frame.
// Writes ink_tradeoff.md, ink_tradeoff.csv and ink_tradeoff_points.csv (for shanshui-bench's
// plots). --quick: one mesh resolution, 256² frames.
//   bench_ink_tradeoff [--out DIR] [--size N] [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "bench_args.h"
#include "bench_output.h"
#include "order_stats.h"
#include "shanshui/core/random.h"
#include "shanshui/mesh/curvature.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/ink_renderer.h"
#include "shanshui/render/shader_program.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
using bench::median;
using bench::quartiles;
using Clock = std::chrono::steady_clock;

struct Surface {
  std::string name;
  mesh::Mesh mesh;
  std::function<double(const glm::dvec3&)> k_max;  // analytic max(|k1|, |k2|) at a surface point
};

Surface sphere(int stacks, bool jitter) {
  mesh::Mesh m = mesh::uvSphere(1.0, stacks, 2 * stacks);
  if (jitter) {  // move vertices along the surface by up to 30 % of an edge, then back onto it
    const double edge = std::numbers::pi / stacks;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
      glm::dvec3 d;
      for (int c = 0; c < 3; ++c)
        d[c] = (static_cast<double>(streamValue(7, i * 3 + c) >> 11) / 9007199254740992.0 - 0.5);
      m.positions[i] = glm::normalize(m.positions[i] + 0.6 * edge * d);
    }
    m.normals = mesh::vertexNormals(m);
  }
  return {jitter ? "sphere (jittered)" : "sphere", std::move(m), [](const glm::dvec3&) { return 1.0; }};
}

Surface torus(int nv) {
  // R = 3, r = 1: max |k| = 1/r everywhere (|cos v / (R + r cos v)| < 1/r).
  mesh::Mesh m = mesh::torus(3.0, 1.0, 2 * nv, nv);
  m.normals = mesh::vertexNormals(m);
  return {"torus", std::move(m), [](const glm::dvec3&) { return 1.0; }};
}

Surface paraboloid(int n) {
  // z = a (x² + y²) over [-1, 1]²: k_circ = 2a / sqrt(1 + 4a²ρ²) ≥ k_merid = 2a / (1 + 4a²ρ²)^1.5.
  const double a = 0.5, cell = 2.0 / (n - 1);
  mesh::Mesh m = mesh::heightGrid(n, n, cell, [&](double x, double y) {
    const double u = x - 1, v = y - 1;
    return a * (u * u + v * v);
  });
  m.normals = mesh::vertexNormals(m);
  return {"paraboloid", std::move(m), [a](const glm::dvec3& p) {
            const double rho2 = (p.x - 1) * (p.x - 1) + (p.y - 1) * (p.y - 1);  // apex at (1, 1)
            return 2 * a / std::sqrt(1 + 4 * a * a * rho2);
          }};
}

struct CurvatureRow {
  double median = 0, p90 = 0, gbuffer_ms = 0, precompute_ms = 0;
};

CurvatureRow measureCurvature(const Surface& s, const char* source, int size) {
  nlohmann::json j = {{"objects", nlohmann::json::array({{{"mesh", "memory"},
                                                          {"recentre", false},
                                                          {"lines", {{"curvature", source}}},
                                                          {"shading", {{"enabled", false}}}}})}};
  const scene::Scene sc = scene::parseScene(j, "bench", ".");
  CurvatureRow row;
  const auto start = Clock::now();
  auto asset = std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(s.mesh, sc.objects[0]));
  row.precompute_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  render::InkRenderer r(sc, {{asset, nullptr}});
  const render::OrbitCamera cam = render::sceneCamera(sc, r.worldBounds(), 1.0, {35, 40, 1.0});
  std::vector<double> ms;
  for (int rep = 0; rep < 7; ++rep) {
    render::OrbitCamera c = cam;
    c.azimuth_deg += 1e-6 * rep;  // not the cached frame
    render::FrameStats st;
    r.render(c, size, size, &st);
    ms.push_back(st.passes.front().gpu_ms);
  }
  std::sort(ms.begin(), ms.end());
  row.gbuffer_ms = ms[ms.size() / 2];
  const image::Image nc = r.normalsAndCurvature();
  const image::Image pos = r.worldPositions();
  const glm::dvec3 eye = cam.eye();
  std::vector<double> err;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      if (pos.at(x, y, 3) < 0.5f) continue;
      const glm::dvec3 p(pos.at(x, y, 0), pos.at(x, y, 1), pos.at(x, y, 2));
      const glm::dvec3 n = glm::normalize(glm::dvec3(nc.at(x, y, 0), nc.at(x, y, 1), nc.at(x, y, 2)));
      if (std::abs(glm::dot(n, glm::normalize(eye - p))) < 0.2) continue;  // grazing: screen derivatives break down
      const double truth = s.k_max(p);
      const double estimate = nc.at(x, y, 3) / asset->feature_size;  // back to 1/world units
      err.push_back(std::abs(estimate - truth) / truth);
    }
  }
  std::sort(err.begin(), err.end());
  row.median = err[err.size() / 2];
  row.p90 = err[err.size() * 9 / 10];
  return row;
}

double cdfAs(double x) {  // shaders/ink/ink_gaussian_cdf.glsl, default
  const double z = std::abs(x) * 0.70710678;
  const double t = 1.0 / (1.0 + 0.3275911 * z);
  const double poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
  return 0.5 + 0.5 * (x < 0 ? -1 : 1) * (1.0 - poly * std::exp(-z * z));
}
double cdfLogistic(double x) {
  return 1.0 / (1.0 + std::exp(-1.702 * x));
}  // the cheaper candidate
double cdfExact(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args =
      bench::parseBenchArgs(argc, argv, "bench_ink_tradeoff [--out DIR] [--size N] [--quick]", {"--size"});
  const std::filesystem::path out = args.out;
  const bool quick = args.quick;
  const int size = args.integer("--size", quick ? 256 : 1024);
  std::filesystem::create_directories(out);
  bench::OutputFile csv(out / "ink_tradeoff.csv"), md(out / "ink_tradeoff.md");
  bench::TradeoffPoints points(out / "ink_tradeoff_points.csv");
  const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
  md << "# Ink renderer: error against run time, and cost\n\nDevice: " << context->description() << "\n\n";

  // 1. Curvature estimators.
  md << "## Curvature per pixel against the analytic max(|k1|, |k2|)\n\n"
     << "Relative error per object pixel (N·V ≥ 0.2) at 512², camera at 40° elevation. `precompute` is the "
        "CPU work on load (cotangent curvature + feature size), `gbuffer` the pass's GPU time.\n\n"
     << "| surface | resolution | vertices | estimator | median error | 90th pct | precompute ms | gbuffer ms |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  csv << "section,surface,resolution,vertices,estimator,median_error,p90_error,precompute_ms,gbuffer_ms\n";
  for (int res : quick ? std::vector<int>{16} : std::vector<int>{16, 64, 256}) {
    std::vector<Surface> surfaces;
    surfaces.push_back(sphere(res, false));
    surfaces.push_back(sphere(res, true));
    surfaces.push_back(torus(res));
    surfaces.push_back(paraboloid(2 * res));
    for (const Surface& s : surfaces) {
      for (const char* source : {"quadric", "cotangent", "screen"}) {
        const CurvatureRow row = measureCurvature(s, source, quick ? 128 : 512);
        char line[512];
        std::snprintf(line, sizeof line, "| %s | %d | %zu | %s | %.1e | %.1e | %.1f | %.2f |\n", s.name.c_str(), res,
                      s.mesh.positions.size(), source, row.median, row.p90, row.precompute_ms, row.gbuffer_ms);
        md << line;
        std::fputs(line, stderr);
        csv << "curvature," << s.name << "," << res << "," << s.mesh.positions.size() << "," << source << ","
            << row.median << "," << row.p90 << "," << row.precompute_ms << "," << row.gbuffer_ms << "\n";
        points.add("curvature per pixel", "90th-percentile relative error of max(|k1|, |k2|)",
                   std::string(source) + ", " + s.name, true, row.precompute_ms + row.gbuffer_ms, row.p90);
      }
    }
  }

  // 2. Gaussian CDF of the smoothed steps.
  md << "\n## Gaussian CDF of the smoothed tone steps against std::erf\n\n"
     << "| formula | max abs error on [-6, 6] | ns per evaluation (CPU) |\n|---|---|---|\n";
  csv << "section,formula,max_abs_error,ns_per_eval\n";
  const std::pair<const char*, double (*)(double)> formulas[] = {{"exact (std::erfc)", cdfExact},
                                                                 {"Abramowitz-Stegun 7.1.26 (default)", cdfAs},
                                                                 {"logistic 1.702 (not used)", cdfLogistic}};
  for (const auto& [name, f] : formulas) {
    double worst = 0;
    for (int i = 0; i <= 120000; ++i) {
      const double x = -6 + 12.0 * i / 120000;
      worst = std::max(worst, std::abs(f(x) - cdfExact(x)));
    }
    volatile double sink = 0;
    const int n = 2000000;
    const auto start = Clock::now();
    for (int i = 0; i < n; ++i) sink = sink + f(-4 + 8.0 * (i & 1023) / 1024);
    const double ns = std::chrono::duration<double, std::nano>(Clock::now() - start).count() / n;
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %.2e | %.1f |\n", name, worst, ns);
    md << line;
    std::fputs(line, stderr);
    csv << "cdf," << name << "," << worst << "," << ns << "\n";
    if (f != cdfExact)  // the reference itself has no error to plot
      points.add("Gaussian CDF of the tone steps, per million evaluations (CPU)",
                 "max |error| against std::erf on [-6, 6]", name, false, ns,
                 worst);  // ns per evaluation = ms per million
  }

  // 3. Ink passes against a Lambert render of the same mesh, interleaved.
  const std::filesystem::path scene_path = std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/scenes/default.json";
  scene::Scene sc = scene::loadScene(scene_path);
  sc.canvas.type = scene::CanvasType::None;  // lines + shading against Lambert: the canvas is measured on its own
  // So are the trees and moss dots (the elements pass), which the sample grew after this
  // comparison was first made: the rows stay lines and shading alone.
  for (scene::Object& o : sc.objects) o.trees.enabled = o.dots.enabled = false;
  scene::AssetCache cache;
  const auto objects = cache.getAll(sc);
  render::InkRenderer ink(sc, objects);
  scene::Scene no_wrinkle = sc;
  no_wrinkle.objects[0].wrinkle.texture.clear();
  render::InkRenderer ink_plain(no_wrinkle, cache.getAll(no_wrinkle));
  const scene::ObjectAsset& a = *objects[0].geometry;
  // With the renderer's front-to-back order too, so the comparison can also be made with
  // a Lambert render given the same triangle order.
  const render::GpuMesh lambert_mesh(a.mesh, a.bounds.centre(), nullptr, true);
  const render::Program lambert({"lambert.vert", "lambert.frag"});
  const render::Framebuffer lambert_fb(size, size, {GL_RGBA8}, true);
  const render::OrbitCamera cam = render::sceneCamera(sc, ink.worldBounds(), 1.0, render::frameKey(sc, 0, 1, 0.0));
  auto lambertFrame = [&](const render::OrbitCamera& c, bool front_to_back) {
    const auto start = Clock::now();
    lambert_fb.bind();
    glClearColor(1, 1, 1, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    lambert.use();
    const glm::dmat4 model = glm::translate(glm::dmat4(1.0), a.bounds.centre());
    lambert.set("u_model", glm::mat4(model));
    lambert.set("u_normal_matrix", glm::mat3(1.0f));
    lambert.set("u_view_projection", c.projection(1.0) * c.view());
    lambert.set("u_light_dir", glm::vec3(glm::normalize(sc.light.direction)));
    if (front_to_back)
      lambert_mesh.drawFrontToBack(glm::vec3(glm::inverse(glm::dmat3(model)) * (c.target - c.eye())));
    else
      lambert_mesh.draw();
    glFinish();
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  };
  std::vector<double> t_lambert, t_sorted, t_ink, t_plain;
  std::map<std::string, std::vector<double>> pass_ms;
  // Each timed frame follows an untimed one of the same render, as in an animation: a
  // frame right after another renderer's pays for the switch (resources out of the caches).
  auto inkFrame = [&](render::InkRenderer& r, render::OrbitCamera c) {
    r.render(c, size, size, nullptr, false);
    glFinish();
    c.azimuth_deg += 1e-5;  // not the cached frame
    const auto start = Clock::now();
    r.render(c, size, size, nullptr, false);
    glFinish();
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  };
  // The ratio is taken per round (each render against the Lambert frame timed just before
  // it) and its median reported: the shared machine's speed drifts between rounds, and a
  // ratio of adjacent frames cancels most of that drift.
  const int rounds = quick ? 3 : 31;
  // r_*: against the Lambert render in the file's triangle order (the plain one); s_*:
  // against one in the renderer's front-to-back order, timed in the same round.
  std::vector<double> r_ink, r_plain, s_ink, s_plain, s_lambert;
  auto lambertThen = [&](const render::OrbitCamera& c, bool front_to_back, render::InkRenderer& r,
                         std::vector<double>& lambert_ms, std::vector<double>& render_ms, std::vector<double>& ratio) {
    lambertFrame(c, front_to_back);
    lambert_ms.push_back(lambertFrame(c, front_to_back));
    render_ms.push_back(inkFrame(r, c));
    ratio.push_back(render_ms.back() / lambert_ms.back());
  };
  for (int rep = 0; rep < rounds; ++rep) {
    render::OrbitCamera c = cam;
    c.azimuth_deg += 0.01 * rep;
    // Each render is timed again after the front-to-back Lambert frame, for its own ratio;
    // the frame times in the table are the first ones.
    std::vector<double> again_ms;
    lambertThen(c, false, ink, t_lambert, t_ink, r_ink);
    lambertThen(c, false, ink_plain, t_lambert, t_plain, r_plain);
    lambertThen(c, true, ink, t_sorted, again_ms, s_ink);
    lambertThen(c, true, ink_plain, t_sorted, again_ms, s_plain);
    // The two orders' first Lambert frames of this round.
    s_lambert.push_back(t_sorted[t_sorted.size() - 2] / t_lambert[t_lambert.size() - 2]);
    render::FrameStats st;
    c.azimuth_deg += 2e-5;
    ink.render(c, size, size, &st, true);
    for (const auto& p : st.passes) pass_ms[p.name].push_back(p.gpu_ms);
  }
  const double l = median(t_lambert), ls = median(t_sorted), k = median(t_ink), p = median(t_plain);
  // Quartiles of the per-round ratios.
  const auto qk = quartiles(r_ink), qp = quartiles(r_plain), sk = quartiles(s_ink), sp = quartiles(s_plain),
             sl = quartiles(s_lambert);
  md << "\n## Frame cost at " << size << "x" << size << ", sample scene (" << ink.triangleCount() << " triangles), "
     << rounds << " interleaved rounds\n\n"
     << "Each round times a Lambert frame then a render (each after an untimed frame of the same render); the "
        "ratio is taken per round and its median and quartiles reported. The plain Lambert render draws the "
        "mesh in its file's triangle order; the renderer draws chunks of it front to back, which the last column "
        "gives the Lambert render too.\n\n"
     << "| render | median ms (wall, glFinish) | ratio to Lambert: median | quartiles | ratio to Lambert in the "
        "renderer's order: median | quartiles |\n|---|---|---|---|---|---|\n";
  char line[512];
  std::snprintf(line, sizeof line,
                "| Lambert, one pass | %.1f | 1.00 | | | |\n"
                "| Lambert, one pass, front-to-back chunks | %.1f | %.2f | %.2f-%.2f | 1.00 | |\n"
                "| lines + shading + wrinkles | %.1f | %.2f | %.2f-%.2f | %.2f | %.2f-%.2f |\n"
                "| lines + shading, no wrinkles | %.1f | %.2f | %.2f-%.2f | %.2f | %.2f-%.2f |\n",
                l, ls, sl[1], sl[0], sl[2], k, qk[1], qk[0], qk[2], sk[1], sk[0], sk[2], p, qp[1], qp[0], qp[2], sp[1],
                sp[0], sp[2]);
  md << line;
  std::fputs(line, stderr);
  csv << "section,render,ms,ratio,ratio_to_front_to_back_lambert\nframe,lambert," << l
      << ",1,\nframe,lambert_front_to_back," << ls << "," << sl[1] << ",1\nframe,ink," << k << "," << qk[1] << ","
      << sk[1] << "\nframe,ink_no_wrinkle," << p << "," << qp[1] << "," << sp[1] << "\n";
  md << "\nPer pass (GPU timestamps, median): ";
  for (const auto& name : ink.passesBuilt()) {
    std::snprintf(line, sizeof line, "%s %.1f ms; ", name.c_str(), median(pass_ms[name]));
    md << line;
  }
  md << "\n";

  // 4. Wrinkle filters: the sample scene's picture with each against trilinear filtering
  // (the closest of the three to the area average a pixel covers), and the frame's cost.
  md << "\n## Wrinkle texture filter, sample scene at " << size << "x" << size << " (interleaved, median of "
     << (quick ? 3 : 15) << ")\n\n"
     << "| filter | mean abs luma difference to trilinear | pixels differing by > 1.5/255 | frame ms |\n"
     << "|---|---|---|---|\n";
  const std::pair<const char*, scene::TextureFilter> filters[] = {{"trilinear", scene::TextureFilter::Trilinear},
                                                                  {"bilinear", scene::TextureFilter::Bilinear},
                                                                  {"nearest", scene::TextureFilter::Nearest}};
  std::vector<std::unique_ptr<render::InkRenderer>> filtered;
  for (const auto& [name, filter] : filters) {
    scene::Scene fs = sc;
    fs.objects[0].wrinkle.filter = filter;
    filtered.push_back(std::make_unique<render::InkRenderer>(fs, objects));
  }
  std::vector<std::vector<double>> t_filter(filtered.size());
  for (int rep = 0; rep < (quick ? 3 : 15); ++rep) {
    render::OrbitCamera c = cam;
    c.azimuth_deg += 0.01 * rep;
    for (std::size_t f = 0; f < filtered.size(); ++f) t_filter[f].push_back(inkFrame(*filtered[f], c));
  }
  std::vector<image::Image> pictures;
  for (auto& r : filtered) pictures.push_back(r->render(cam, size, size).colour(0).download(3));
  for (std::size_t f = 0; f < filtered.size(); ++f) {
    double sum = 0, differ = 0;
    const std::size_t n = static_cast<std::size_t>(size) * size;
    for (std::size_t i = 0; i < n; ++i) {
      const float* pa = &pictures[f].pixels[i * 3];
      const float* pb = &pictures[0].pixels[i * 3];
      const double d = std::abs(0.3 * (pa[0] - pb[0]) + 0.59 * (pa[1] - pb[1]) + 0.11 * (pa[2] - pb[2]));
      sum += d;
      differ += d > 1.5 / 255 ? 1 : 0;
    }
    const double ms_f = median(t_filter[f]);
    const char* name = filters[f].first;
    std::snprintf(line, sizeof line, "| %s | %.2e | %.1f %% | %.1f |\n", name, sum / n, 100.0 * differ / n, ms_f);
    md << line;
    std::fputs(line, stderr);
    csv << "filter," << name << "," << ms_f << "," << sum / n << "\n";
    if (f > 0)
      points.add("wrinkle texture filter, sample scene frame", "mean |luma - trilinear|", name, false, ms_f, sum / n);
  }
  return 0;
}
