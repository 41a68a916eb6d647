// Error against run time for image quilting (SPEC.md sections 3 and 12): every sample
// texture, each search mode and seam mode; the search error is the chosen block's overlap
// error relative to the exhaustive search's minimum. Writes quilt_tradeoff.csv (one row
// per texture and configuration), quilt_tradeoff.md (means over textures) and
// quilt_tradeoff_points.csv (for shanshui-bench's plots). --quick: three textures, 128².
//   bench_quilt_tradeoff [--out DIR] [--size N] [--block B] [--quick]
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_data.h"
#include "bench_output.h"
#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "shanshui/texsynth/quilt_metrics.h"
#include "shanshui/texsynth/quilting.h"
#include "tradeoff_points.h"

namespace {

using namespace shanshui;
namespace fs = std::filesystem;

struct Config {
  std::string name;
  texsynth::SearchMode search;
  texsynth::SeamMode seam;
  bool tileable;
};

struct Row {
  double seconds, ratio, violations, overlapError, seamError, coherence, verbatim, coverage, wrapError;
};

}  // namespace

int main(int argc, char** argv) {
  const bench::BenchArgs args = bench::parseBenchArgs(
      argc, argv, "bench_quilt_tradeoff [--out DIR] [--size N] [--block B] [--quick]", {"--size", "--block"});
  const fs::path out = args.out;
  const bool quick = args.quick;
  const int size = args.integer("--size", quick ? 128 : 256), block = args.integer("--block", 32);
  std::vector<fs::path> files = bench::textureScans();
  if (quick && files.size() > 3) files.resize(3);
  fs::create_directories(out);

  using texsynth::SeamMode;
  using texsynth::SearchMode;
  const std::vector<Config> configs = {
      {"fft + cut", SearchMode::Fft, SeamMode::Cut, false},
      {"exhaustive + cut", SearchMode::Exhaustive, SeamMode::Cut, false},
      {"random + cut", SearchMode::Random, SeamMode::Cut, false},
      {"fft + graphcut", SearchMode::Fft, SeamMode::GraphCut, false},
      {"fft + none", SearchMode::Fft, SeamMode::None, false},
      {"fft + cut, tileable", SearchMode::Fft, SeamMode::Cut, true},
  };
  bench::OutputFile csv(out / "quilt_tradeoff.csv");
  csv << "texture,config,seconds,search_error_ratio,search_rule_violations,overlap_error_per_pixel,seam_error_per_edge,"
         "coherence_mean,verbatim_copy_ratio,sample_coverage,wrap_seam_error\n";
  std::map<std::string, std::vector<Row>> rows;
  for (const fs::path& f : files) {
    const image::Image sample = image::loadImage(f);
    for (const Config& c : configs) {
      texsynth::QuiltOptions o;
      o.width = o.height = size;
      o.block = std::min({block, sample.width, sample.height});
      o.search = c.search;
      o.seam = c.seam;
      o.tileable = c.tileable;
      o.threads = 1;
      const texsynth::QuiltResult timed = texsynth::quilt(sample, o);
      o.audit = true;
      const texsynth::QuiltResult audited = texsynth::quilt(sample, o);
      SHANSHUI_CHECK(audited.source == timed.source);  // the audit must not change the result
      const texsynth::QuiltMetrics m = texsynth::measureQuilt(sample, timed, o.block);
      const Row r{timed.stats.seconds,
                  audited.stats.search_error_ratio,
                  audited.stats.search_rule_violations,
                  timed.stats.overlap_error_per_pixel,
                  m.seam_error_per_edge,
                  m.coherence_mean,
                  m.verbatim_copy_ratio,
                  m.sample_coverage,
                  m.wrap_seam_error};
      rows[c.name].push_back(r);
      csv << f.filename().string() << "," << c.name << "," << r.seconds << "," << r.ratio << "," << r.violations << ","
          << r.overlapError << "," << r.seamError << "," << r.coherence << "," << r.verbatim << "," << r.coverage << ","
          << r.wrapError << "\n";
      std::fprintf(stderr, "%-24s %-22s %7.3f s  ratio %.3f\n", f.filename().c_str(), c.name.c_str(), r.seconds,
                   r.ratio);
    }
  }

  bench::OutputFile md(out / "quilt_tradeoff.md");
  md << "Image quilting, " << size << "x" << size << " output, block " << block << " (or the sample size), "
     << "overlap B/6, tolerance 0.1, one thread; means over " << files.size() << " textures.\n\n"
     << "| configuration | seconds | time / fft | chosen / exhaustive min | blocks outside the exact rule | overlap "
        "error per px "
        "| seam error per edge | coherence (nearest-patch SSD per px) | verbatim copy ratio | sample coverage "
        "| wrap seam error |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto mean = [](const std::vector<Row>& v, double Row::*field) {
    double s = 0;
    for (const Row& r : v) s += r.*field;
    return s / static_cast<double>(v.size());
  };
  const double fftSeconds = mean(rows["fft + cut"], &Row::seconds);
  char line[512];
  for (const Config& c : configs) {
    const auto& v = rows[c.name];
    std::snprintf(line, sizeof line, "| %s | %.3f | %.1f | %.3f | %.3f | %.4f | %.4f | %.4f | %.4f | %.3f | %.4f |\n",
                  c.name.c_str(), mean(v, &Row::seconds), mean(v, &Row::seconds) / fftSeconds, mean(v, &Row::ratio),
                  mean(v, &Row::violations), mean(v, &Row::overlapError), mean(v, &Row::seamError),
                  mean(v, &Row::coherence), mean(v, &Row::verbatim), mean(v, &Row::coverage), mean(v, &Row::wrapError));
    md << line;
  }
  bench::TradeoffPoints points(out / "quilt_tradeoff_points.csv");
  for (const Config& c : configs) {
    const auto& v = rows[c.name];
    points.add("quilting: overlap error", "overlap error per pixel (mean over textures)", c.name, false,
               1000.0 * mean(v, &Row::seconds), mean(v, &Row::overlapError));
    points.add("quilting: seam error", "seam error per edge (mean over textures)", c.name, false,
               1000.0 * mean(v, &Row::seconds), mean(v, &Row::seamError));
  }
  std::fprintf(stderr, "wrote %s and %s\n", (out / "quilt_tradeoff.csv").c_str(), (out / "quilt_tradeoff.md").c_str());
  return 0;
}
