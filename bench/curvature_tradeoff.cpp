// Error against run time for object-space curvature (SPEC.md sections 6 and 12): both
// estimators (the two-ring quadric fit, the renderer's default, and the cotangent formula)
// on a unit sphere and a torus (R = 3, r = 1) at increasing resolution; error = median and
// 95th-percentile relative error of the mean curvature against the analytic value. Writes
// curvature_tradeoff.md, .csv and _points.csv (for shanshui-bench's plots).
//   bench_curvature_tradeoff [--out DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_output.h"
#include "shanshui/mesh/curvature.h"
#include "shanshui/mesh/shapes.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
using Clock = std::chrono::steady_clock;

struct Surface {
  mesh::Mesh mesh;
  std::vector<double> mean;  // analytic |H| per vertex
};

Surface sphere(int stacks) {
  Surface s{mesh::uvSphere(1.0, stacks, 2 * stacks), {}};
  s.mean.assign(s.mesh.positions.size(), 1.0);
  return s;
}

Surface torus(int nv) {
  const double big = 3, small = 1;
  std::vector<double> cosV;
  Surface s{mesh::torus(big, small, 2 * nv, nv, &cosV), {}};
  for (double c : cosV) s.mean.push_back((big + 2 * small * c) / (2 * small * (big + small * c)));
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(argc, argv, "bench_curvature_tradeoff [--out DIR] [--quick]");
  const std::filesystem::path out = args.out;
  const bool quick = args.quick;
  std::filesystem::create_directories(out);
  bench::OutputFile csv(out / "curvature_tradeoff.csv"), md(out / "curvature_tradeoff.md");
  bench::TradeoffPoints points(out / "curvature_tradeoff_points.csv");
  csv << "surface,estimator,resolution,vertices,milliseconds,median_rel_error,p95_rel_error\n";
  md << "Object-space mean curvature against the analytic value (relative error of |H| per vertex); "
        "quadric = two-ring quadric fit (default), cotangent = the cotangent formula.\n\n"
     << "| surface | estimator | resolution | vertices | ms | median error | 95th percentile |\n"
        "|---|---|---|---|---|---|---|\n";
  const std::vector<int> resolutions = quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64, 128, 256};
  for (const char* name : {"sphere", "torus"}) {
    for (const char* estimator : {"quadric", "cotangent"}) {
      const bool fit = std::string(estimator) == "quadric";
      for (int res : resolutions) {
        const Surface s = std::string(name) == "sphere" ? sphere(res) : torus(res);
        const int repeats = std::max(1, (quick ? 20000 : 200000) / static_cast<int>(s.mesh.positions.size()));
        mesh::VertexCurvature c;
        const auto start = Clock::now();
        for (int r = 0; r < repeats; ++r)
          c = fit ? mesh::estimateCurvatureByFit(s.mesh) : mesh::estimateCurvature(s.mesh);
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count() / repeats;
        std::vector<double> e;
        for (std::size_t i = 0; i < s.mean.size(); ++i)
          e.push_back(std::abs(std::abs(c.mean[i]) - s.mean[i]) / s.mean[i]);
        std::sort(e.begin(), e.end());
        const double median = e[e.size() / 2], p95 = e[e.size() * 95 / 100];
        csv << name << "," << estimator << "," << res << "," << s.mesh.positions.size() << "," << ms << "," << median
            << "," << p95 << "\n";
        points.add("object-space curvature", "95th-percentile relative error of |H|",
                   std::string(estimator) + ", " + name, true, ms, p95);
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %s | %d | %zu | %.3f | %.2e | %.2e |\n", name, estimator, res,
                      s.mesh.positions.size(), ms, median, p95);
        md << line;
        std::fputs(line, stderr);
      }
    }
  }
  return 0;
}
