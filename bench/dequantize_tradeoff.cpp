// Error against run time for smoothing heights stored in steps (terrain::dequantize): a
// Gaussian hill 400 m high (steep) and one 40 m high (gentle), stored in whole metres, at
// each blur width and number of sweeps; error = root mean square error of the discrete
// Laplacian (the curvature the lines are drawn from) and of the heights against the true
// hill. The stored grid's own errors are the row with 0 sweeps. Writes
// dequantize_tradeoff.md, .csv and _points.csv (for shanshui-bench's plots).
//   bench_dequantize_tradeoff [--out DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_output.h"
#include "shanshui/terrain/heightfield.h"
#include "stepped_hill.h"
#include "tradeoff_points.h"

int main(int argc, char** argv) {
  using namespace shanshui;
  using Clock = std::chrono::steady_clock;
  const bench::BenchArgs args = bench::parseBenchArgs(argc, argv, "bench_dequantize_tradeoff [--out DIR] [--quick]");
  std::filesystem::create_directories(args.out);
  bench::OutputFile csv(args.out / "dequantize_tradeoff.csv"), md(args.out / "dequantize_tradeoff.md");
  bench::TradeoffPoints points(args.out / "dequantize_tradeoff_points.csv");
  csv << "hill_m,sigma_cells,sweeps,milliseconds,laplacian_rms_m,height_rms_m\n";
  md << "Heights stored in whole metres smoothed within their steps (`terrain::dequantize`), on a Gaussian hill of "
        "200 x 200 cells; error against the true hill: RMS of the discrete Laplacian and of the heights (m). "
        "Default: sigma "
     << terrain::kDequantizeSigma << " cells, " << terrain::kDequantizeSweeps << " sweeps.\n\n"
     << "| hill | sigma (cells) | sweeps | ms | Laplacian error | height error |\n|---|---|---|---|---|---|\n";
  const std::vector<double> sigmas = args.quick ? std::vector<double>{1.5} : std::vector<double>{1.0, 1.5, 2.0, 3.0};
  const std::vector<int> sweeps = args.quick ? std::vector<int>{0, 1, 4} : std::vector<int>{0, 1, 2, 4, 8};
  const int repeats = args.quick ? 1 : 5;
  for (double height : {400.0, 40.0}) {
    for (double sigma : sigmas) {
      for (int n : sweeps) {
        terrain::Heightfield h;
        double ms = 1e300;  // the fastest of the repeats: the least disturbed by the machine
        for (int r = 0; r < repeats; ++r) {
          h = test::steppedHill(height, 1.0);
          const auto start = Clock::now();
          if (n > 0) terrain::dequantize(h, sigma, n);
          ms = std::min(ms, std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        }
        const auto [z, laplacian] = test::hillErrors(h, height);
        csv << height << "," << sigma << "," << n << "," << ms << "," << laplacian << "," << z << "\n";
        char label[64];
        std::snprintf(label, sizeof label, "%.0f m hill, sigma %.1f", height, sigma);
        points.add("dequantize", "RMS error of the Laplacian (m)", label, true, ms, laplacian);
        char line[256];
        std::snprintf(line, sizeof line, "| %.0f m | %.1f | %d | %.2f | %.4f | %.4f |\n", height, sigma, n, ms,
                      laplacian, z);
        md << line;
        std::fputs(line, stderr);
      }
    }
  }
  return 0;
}
