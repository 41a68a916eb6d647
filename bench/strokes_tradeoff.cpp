// Error against run time for the brush strokes' knobs (issue 24): the spline's sampling
// step and the span chains are subdivided to, on a sphere seen from above its pole, whose
// silhouette has a known projected radius; and linking's gap and turn, on the same sphere
// (one closed chain is the answer) and a torus (two). Writes strokes_tradeoff.md, .csv and
// _points.csv (for shanshui-bench's plots).
//   bench_strokes_tradeoff [--out DIR] [--quick]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "bench_args.h"
#include "bench_output.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/strokes/chains.h"
#include "shanshui/strokes/edges.h"
#include "shanshui/strokes/visibility.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

struct Scene {
  mesh::Mesh mesh;
  glm::dvec3 eye;
  glm::dmat4 vp;
  std::vector<strokes::ScreenSegment> seen;
};

Scene silhouettes(mesh::Mesh m, glm::dvec3 eye, int size) {
  Scene s;
  s.mesh = std::move(m);
  s.eye = eye;
  s.vp = glm::perspective(glm::radians(40.0), 1.0, 0.1, 100.0) * glm::lookAt(eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  const strokes::EdgeGraph g = strokes::buildEdgeGraph(s.mesh);
  std::vector<strokes::FeatureEdge> edges;
  for (const strokes::FeatureEdge& e : strokes::featureEdges(g, s.mesh, eye, 180.0))
    if (e.kinds & strokes::kSilhouette) edges.push_back(e);
  const strokes::ReferenceImage ref = strokes::rasterizeReference(s.mesh, s.vp, size, size);
  s.seen = strokes::visibleSegments(edges, g, s.mesh, s.vp, ref);
  return s;
}

template <typename F>
double millis(F&& f, int repeats) {
  const auto start = Clock::now();
  for (int i = 0; i < repeats; ++i) f();
  return 1000.0 * std::chrono::duration<double>(Clock::now() - start).count() / repeats;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(argc, argv, "bench_strokes_tradeoff [--out DIR] [--quick]", {});
  fs::create_directories(args.out);
  const int size = args.quick ? 256 : 768;
  const int repeats = args.quick ? 3 : 20;
  // The sphere's smooth silhouette from (0, 0, d): the cone tangent to it has half-angle
  // asin(R / d), so the projected radius is f · tan(asin(R / d)) with f = size / 2 / tan(20°).
  const double radius = 1.0, distance = 4.0;
  const Scene sphere = silhouettes(mesh::uvSphere(radius, 64, 128), {0, 0, distance}, size);
  const double focal = 0.5 * size / std::tan(glm::radians(20.0));
  const double truth = focal * std::tan(std::asin(radius / distance));
  const std::vector<strokes::Chain> sphereChains = strokes::linkSegments(sphere.seen);

  bench::OutputFile md(args.out / "strokes_tradeoff.md");
  bench::OutputFile csv(args.out / "strokes_tradeoff.csv");
  csv << "knob,value,ms,error_px,chains\n";
  bench::TradeoffPoints points(args.out / "strokes_tradeoff_points.csv");
  md << "## Spline: sampling step and subdivision span against the true silhouette\n\n"
     << "A sphere of radius 1 seen from 4 above its pole at " << size << "² (40° field): its smooth silhouette "
     << "projects to a circle of " << truth << " px. Error: mean |distance to the centre − that radius| over the "
     << "stroke's points (the mesh's 128-gon alone is off by its facets).\n\n"
     << "| step (px) | span (px) | ms per stroke | points | error (px) |\n|---|---|---|---|---|\n";
  char line[256];
  const glm::dvec2 centre(0.5 * size);
  for (const double span : {1e9, 8.0, 4.0}) {
    for (const double step : {8.0, 4.0, 2.0, 1.0, 0.5}) {
      std::vector<glm::dvec2> path;
      const double ms = millis(
          [&] {
            path = strokes::cardinalSpline(span < 1e8 ? strokes::subdivided(sphereChains[0], span) : sphereChains[0],
                                           0.0, step);
          },
          repeats);
      double error = 0.0;
      for (const glm::dvec2& p : path) error += std::abs(glm::length(p - centre) - truth);
      error /= static_cast<double>(path.size());
      std::snprintf(line, sizeof line, "| %.1f | %s | %.3f | %zu | %.3f |\n", step,
                    span < 1e8 ? std::to_string(static_cast<int>(span)).c_str() : "none", ms, path.size(), error);
      md << line;
      csv << "spline_step_span" << (span < 1e8 ? static_cast<int>(span) : 0) << "," << step << "," << ms << "," << error
          << ",1\n";
      points.add("brush strokes: spline sampling step", "mean error to the true silhouette (px)",
                 span < 1e8 ? "spans of " + std::to_string(static_cast<int>(span)) + " px" : "chain's points alone",
                 true, ms, error);
      std::fprintf(stderr, "%s", line);
    }
  }

  // Linking: how many chains the known answer (sphere 1, torus 2) comes out as.
  const Scene torus = silhouettes(mesh::torus(3.0, 1.0, 96, 48), {0, 0, 12}, size);
  md << "\n## Linking: gap and turn against the number of chains (sphere: 1, torus: 2)\n\n"
     << "| max gap (px) | max turn (°) | sphere: ms | chains | torus: ms | chains |\n|---|---|---|---|---|---|\n";
  for (const double gap : {0.0, 1.0, 5.0, 20.0}) {
    for (const double turn : {2.0, 10.0, 45.0, 120.0}) {
      std::size_t a = 0, b = 0;
      const double msA = millis([&] { a = strokes::linkSegments(sphere.seen, {turn, gap}).size(); }, repeats);
      const double msB = millis([&] { b = strokes::linkSegments(torus.seen, {turn, gap}).size(); }, repeats);
      std::snprintf(line, sizeof line, "| %.0f | %.0f | %.3f | %zu | %.3f | %zu |\n", gap, turn, msA, a, msB, b);
      md << line;
      csv << "link_gap_turn" << turn << "," << gap << "," << msA + msB << ","
          << std::abs(static_cast<double>(a) - 1.0) + std::abs(static_cast<double>(b) - 2.0) << "," << a + b << "\n";
      points.add("brush strokes: linking gap and turn", "chains off the answer (sphere 1, torus 2)",
                 "max turn " + std::to_string(static_cast<int>(turn)) + " deg, gap 0-20 px", true, msA + msB,
                 std::abs(static_cast<double>(a) - 1.0) + std::abs(static_cast<double>(b) - 2.0));
      std::fprintf(stderr, "%s", line);
    }
  }
  std::fprintf(stderr, "wrote %s\n", (args.out / "strokes_tradeoff.md").c_str());
  return 0;
}
