// shanshui-quilt: synthesise a large wrinkle texture from a sample by image quilting.
#include <chrono>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/core/parse.h"
#include "shanshui/image/image_io.h"
#include "shanshui/texsynth/quilt_metrics.h"
#include "shanshui/texsynth/quilting.h"
#include "tool_main.h"

namespace {

using namespace shanshui;

nlohmann::json reportJson(const std::string& input, const std::string& output, const texsynth::QuiltOptions& o,
                          const texsynth::QuiltStats& s, const texsynth::QuiltMetrics& m) {
  nlohmann::json j;
  j["input"] = input;
  j["output"] = output;
  j["options"] = {{"width", o.width},
                  {"height", o.height},
                  {"block", o.block},
                  {"overlap", o.resolvedOverlap()},
                  {"tolerance", o.tolerance},
                  {"error_floor", o.error_floor},
                  {"seed", o.seed},
                  {"seam", texsynth::seamModeName(o.seam)},
                  {"search", texsynth::searchModeName(o.search)},
                  {"tileable", o.tileable},
                  {"threads", s.threads}};
  j["seconds"] = s.seconds;
  j["blocks"] = s.blocks;
  j["blocks_x"] = s.blocks_x;
  j["blocks_y"] = s.blocks_y;
  j["waves"] = s.waves;
  j["mean_candidates"] = s.mean_candidates;
  j["overlap_pixels"] = s.overlap_pixels;
  j["overlap_error_per_pixel"] = s.overlap_error_per_pixel;
  j["seam_edges"] = m.seam_edges;
  j["seam_error_per_edge"] = m.seam_error_per_edge;
  j["mean_seam_error_per_overlap_pixel"] = m.seam_error_per_overlap_pixel;
  j["coherence"] = {{"mean", m.coherence_mean}, {"max", m.coherence_max}};
  j["source_usage"] = {
      {"sample_coverage", m.sample_coverage}, {"cv", m.usage_cv}, {"max_over_mean", m.usage_max_ratio}};
  j["verbatim_copy_ratio"] = m.verbatim_copy_ratio;
  j["largest_copy_blocks"] = m.largest_copy_blocks;
  j["mean_region_pixels"] = m.mean_region_pixels;
  j["wrap_seam_error"] = m.wrap_seam_error;
  j["wrap_seam_edges"] = m.wrap_seam_edges;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Synthesises a texture of any size from a sample by image quilting (Efros & Freeman\n"
      "2001; SPEC.md section 3): blocks chosen by FFT overlap search, pasted along the\n"
      "minimum error boundary cut or a graph cut; optionally tileable.",
      "shanshui-quilt"};
  app.footer(
      "Example:\n  shanshui-quilt sample.png -o wrinkle.png --size 1024x1024 --block 48 --tileable "
      "--report quilt.json");
  std::string input, output, size, reportPath, seam = "cut", search = "fft";
  texsynth::QuiltOptions options;
  app.add_option("input", input, "sample image (PNG, JPEG, TIFF, EXR, ...)")->required();
  app.add_option("-o,--output", output, "synthesised texture; the extension picks the format")->required();
  app.add_option("--size", size, "output size WxH")->required();
  app.add_option("--block", options.block, "block size B in pixels (>= 3, at most the sample size)")->default_val(48);
  app.add_option("--overlap", options.overlap, "overlap O in pixels, 1 <= O < B (default: B/6)")
      ->check(tools::integerIn(1, 100000));
  app.add_option("--tolerance", options.tolerance, "accept blocks within (1 + T) of the best overlap error")
      ->default_val(0.1);
  app.add_option("--seed", options.seed, "random seed; the same seed gives the same output")
      ->check(tools::integerIn(0))
      ->default_val(1);
  app.add_option("--seam", seam, "how blocks are joined")
      ->check(CLI::IsMember({"cut", "graphcut", "none"}))
      ->default_val("cut");
  app.add_flag("--tileable", options.tileable, "make the output tile seamlessly");
  app.add_option("--search", search, "overlap search: fft (fast, exact), exhaustive (reference), random (baseline)")
      ->check(CLI::IsMember({"fft", "exhaustive", "random"}))
      ->default_val("fft");
  app.add_option("--threads", options.threads, "worker threads (0 = all cores); the output does not depend on it")
      ->check(tools::integerIn(0, 1024))
      ->default_val(0);
  app.add_option("--report", reportPath, "write timings and quality metrics as JSON");
  bool smallest = false;
  app.add_flag("--smallest", smallest, "compress PNG/TIFF/EXR output hardest (slower); default: fast compression");
  return tools::runBatchableTool(app, argc, argv, [&] {
    const Size2 outSize = parseSize(size, "--size");
    if (static_cast<long long>(outSize.width) * outSize.height > image::kMaxImagePixels) {
      throw makeError("--size: ", size, " is more than the largest image written (16384 x 16384 pixels)");
    }
    options.width = outSize.width;
    options.height = outSize.height;
    options.seam = seam == "graphcut" ? texsynth::SeamMode::GraphCut
                   : seam == "none"   ? texsynth::SeamMode::None
                                      : texsynth::SeamMode::Cut;
    options.search = search == "exhaustive" ? texsynth::SearchMode::Exhaustive
                     : search == "random"   ? texsynth::SearchMode::Random
                                            : texsynth::SearchMode::Fft;
    OutputSet outputs({input});
    outputs.declare(output, "-o", image::writableImageExtensions());
    if (!reportPath.empty()) outputs.declare(reportPath, "--report", {".json"});

    image::ImageInfo info;
    const image::Image sample = image::loadImage(input, &info);
    if (info.alpha_only) throw makeError(input, ": the image has only an alpha channel; expected grey or colour");
    texsynth::validate(options, sample.width, sample.height, input);

    using Clock = std::chrono::steady_clock;
    auto lastPrint = Clock::now();
    bool printed = false;
    options.progress = [&](int done, int total) {
      const auto now = Clock::now();
      if (done < total && now - lastPrint < std::chrono::seconds(1)) return;
      if (done == total && !printed) return;  // short runs stay quiet
      lastPrint = now;
      printed = true;
      std::fprintf(stderr, "quilt: %d/%d blocks (%d%%)\n", done, total, 100 * done / total);
    };
    const texsynth::QuiltResult result = texsynth::quilt(sample, options, input);
    const image::PixelDepth depth =
        image::closestDepth(output, info.depth == image::PixelDepth::UInt8    ? image::PixelDepth::UInt8
                                    : info.depth == image::PixelDepth::UInt16 ? image::PixelDepth::UInt16
                                                                              : image::PixelDepth::Float);
    outputs.stage(output, image::encodeImage(result.image, output, depth, {.smallest = smallest}));
    if (!reportPath.empty()) {
      const texsynth::QuiltMetrics m = texsynth::measureQuilt(sample, result, options.block);
      const nlohmann::json j = reportJson(input, output, options, result.stats, m);
      outputs.stage(reportPath, tools::jsonText(j, reportPath));
    }
    outputs.commit();
    const texsynth::QuiltStats& s = result.stats;
    std::fprintf(stderr, "%s: %dx%d from %d blocks in %.2f s (%d threads); overlap error %.3g per pixel\n",
                 output.c_str(), options.width, options.height, s.blocks, s.seconds, s.threads,
                 s.overlap_error_per_pixel);
  });
}
