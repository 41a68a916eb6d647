// Error against run time for making a coarse DEM finer (terrain::upsample): a landform known
// everywhere (two crossed waves) sampled at 6, 10 and 16 cells a wavelength on a 120 x 91
// grid (the BC coast's), made 1 to 8 times finer; error = the largest and the RMS height
// misses of the mesh it gives (straight lines between its samples, as its triangles draw)
// against the landform, at 16 points a coarse cell, as a share of the waves' amplitude.
// Factor 1 is the coarse grid's own mesh. The same with OpenCV's cubic (cv::remap,
// INTER_CUBIC, a = −0.75) shows why upsample has its own Catmull-Rom. Writes
// upsample_tradeoff.md, .csv and _points.csv (for shanshui-bench's plots).
//   bench_upsample_tradeoff [--out DIR] [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "bench_args.h"
#include "bench_output.h"
#include "shanshui/terrain/heightfield.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;

// Amplitude 1; `wavelength` in coarse cells.
double landform(double x, double y, double wavelength) {
  const double k = 2.0 * M_PI / wavelength;
  return 0.7 * std::sin(k * x + 0.3) * std::cos(0.8 * k * y) + 0.3 * std::cos(0.6 * k * (x + y));
}

terrain::Heightfield coarseGrid(double wavelength) {
  terrain::Heightfield h;
  h.columns = 120;
  h.rows = 91;
  for (int r = 0; r < h.rows; ++r)
    for (int c = 0; c < h.columns; ++c) h.elevation.push_back(landform(c, r, wavelength));
  return h;
}

// OpenCV's cubic at the same positions (whole numbers at the stored samples).
terrain::Heightfield opencvCubic(const terrain::Heightfield& h, int factor) {
  cv::Mat z(h.rows, h.columns, CV_64F, const_cast<double*>(h.elevation.data()));
  const int w = (h.columns - 1) * factor + 1, n = (h.rows - 1) * factor + 1;
  cv::Mat mx(n, w, CV_32F), my(n, w, CV_32F), fine;
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < w; ++c) {
      mx.at<float>(r, c) = static_cast<float>(static_cast<double>(c) / factor);
      my.at<float>(r, c) = static_cast<float>(static_cast<double>(r) / factor);
    }
  }
  cv::remap(z, fine, mx, my, cv::INTER_CUBIC, cv::BORDER_REPLICATE);
  terrain::Heightfield out = h;
  out.columns = w;
  out.rows = n;
  out.elevation.assign(fine.begin<double>(), fine.end<double>());
  return out;
}

// Largest and RMS miss of the grid's bilinear surface (`factor` samples a coarse cell)
// against the landform, inside (two coarse cells in from the edge), 16 points a coarse cell.
std::pair<double, double> misses(const terrain::Heightfield& fine, int factor, double wavelength) {
  double worst = 0.0, sum = 0.0;
  std::size_t count = 0;
  for (double y = 2.0; y < 88.0; y += 0.25) {
    for (double x = 2.0; x < 117.0; x += 0.25) {
      const double u = x * factor, v = y * factor;
      const int c = std::min(static_cast<int>(u), fine.columns - 2), r = std::min(static_cast<int>(v), fine.rows - 2);
      const double fx = u - c, fy = v - r;
      const double z = (1 - fy) * ((1 - fx) * fine.at(c, r) + fx * fine.at(c + 1, r)) +
                       fy * ((1 - fx) * fine.at(c, r + 1) + fx * fine.at(c + 1, r + 1));
      const double d = z - landform(x, y, wavelength);
      worst = std::max(worst, std::abs(d));
      sum += d * d;
      ++count;
    }
  }
  return {worst, std::sqrt(sum / static_cast<double>(count))};
}

}  // namespace

int main(int argc, char** argv) {
  using Clock = std::chrono::steady_clock;
  const bench::BenchArgs args = bench::parseBenchArgs(argc, argv, "bench_upsample_tradeoff [--out DIR] [--quick]");
  std::filesystem::create_directories(args.out);
  bench::OutputFile csv(args.out / "upsample_tradeoff.csv"), md(args.out / "upsample_tradeoff.md");
  bench::TradeoffPoints points(args.out / "upsample_tradeoff_points.csv");
  csv << "method,wavelength_cells,factor,milliseconds,largest_miss,rms_miss\n";
  md << "A coarse grid (120 x 91, the BC coast's) made finer (`terrain::upsample`), on a landform of two crossed "
        "waves of amplitude 1 sampled at 6, 10 and 16 cells a wavelength; the miss of the mesh it gives (straight "
        "lines between its samples) against the landform, largest and RMS, in units of the amplitude. Factor 1 is the "
        "coarse grid's own mesh; a lone DEM under 400 samples a side is made finer until it has them (the coast: "
        "4).\n\n"
     << "| method | cells a wave | factor | ms | largest miss | RMS miss |\n|---|---|---|---|---|---|\n";
  const std::vector<int> factors = args.quick ? std::vector<int>{1, 2, 4} : std::vector<int>{1, 2, 3, 4, 6, 8};
  const std::vector<double> wavelengths = args.quick ? std::vector<double>{10.0} : std::vector<double>{6.0, 10.0, 16.0};
  const int repeats = args.quick ? 1 : 5;
  for (const char* method : {"catmull-rom (upsample)", "opencv cubic"}) {
    const bool ours = method[0] == 'c';
    for (double wavelength : wavelengths) {
      const terrain::Heightfield coarse = coarseGrid(wavelength);
      for (int factor : factors) {
        if (!ours && factor == 1) continue;  // the same coarse mesh as above
        terrain::Heightfield fine;
        double ms = 1e300;  // the fastest of the repeats: the least disturbed by the machine
        for (int k = 0; k < repeats; ++k) {
          const auto start = Clock::now();
          if (ours) {
            fine = coarse;
            terrain::upsample(fine, factor, "bench");
          } else {
            fine = opencvCubic(coarse, factor);
          }
          ms = std::min(ms, std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        }
        const auto [worst, rms] = misses(fine, factor, wavelength);
        csv << "\"" << method << "\"," << wavelength << "," << factor << "," << ms << "," << worst << "," << rms
            << "\n";
        char label[96];
        std::snprintf(label, sizeof label, "%s, %.0f cells a wave", method, wavelength);
        points.add("upsampling a coarse DEM", "RMS miss against the landform (amplitude 1)", label, true, ms, rms);
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %.0f | %d | %.2f | %.4f | %.4f |\n", method, wavelength, factor, ms,
                      worst, rms);
        md << line;
        std::fputs(line, stderr);
      }
    }
  }
  return 0;
}
