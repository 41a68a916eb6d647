// shanshui-enhance: stretch the contrast of a scanned wrinkle (cun) sample (seed 001, Eq. 4).
#include <cstdio>
#include <utility>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/parse.h"
#include "shanshui/image/image_io.h"
#include "shanshui/texsynth/enhance.h"
#include "tool_main.h"

int main(int argc, char** argv) {
  using namespace shanshui;
  CLI::App app{
      "Contrast-enhances a texture sample with the piecewise linear grey-level transform\n"
      "(SPEC.md section 2): values at or below A map to C, at or above B to D, linear between.\n"
      "By default A and B are the 1st and 99th percentiles and the output is grey.",
      "shanshui-enhance"};
  app.footer("Example:\n  shanshui-enhance scan.jpg -o sample.png --auto 2:98 --depth 16");
  std::string input, output, range, autoRange = "1:99", to = "0:1", depth;
  bool colour = false;
  app.add_option("input", input, "image to enhance (PNG, JPEG, TIFF, EXR, ...)")->required();
  app.add_option("-o,--output", output, "enhanced image; the extension picks the format")->required();
  auto* rangeOpt = app.add_option("--range", range, "input range A:B in [0,1] mapped to C:D");
  app.add_option("--auto", autoRange, "input range from these histogram percentiles, PLO:PHI")
      ->default_val("1:99")
      ->excludes(rangeOpt);
  app.add_option("--to", to, "output range C:D in [0,1]")->default_val("0:1");
  app.add_flag("--color,--colour", colour, "map every colour channel instead of converting to grey");
  app.add_option("--depth", depth,
                 "output sample depth: 8, 16 or float (default: the input's, or the nearest the format stores)");
  bool smallest = false;
  app.add_flag("--smallest", smallest, "compress PNG/TIFF/EXR output hardest (slower); default: fast compression");
  return tools::runBatchableTool(app, argc, argv, [&] {
    texsynth::EnhanceOptions options;
    if (!range.empty()) {
      const auto [a, b] = parsePair(range, "--range");
      options.input_range = texsynth::ValueRange{a, b};
    } else {
      std::tie(options.low_percentile, options.high_percentile) = parsePair(autoRange, "--auto");
    }
    const auto [c, d] = parsePair(to, "--to");
    options.output_range = {c, d};
    options.colour = colour;
    std::optional<image::PixelDepth> outDepth;
    if (!depth.empty()) outDepth = image::parseDepth(depth);
    OutputSet outputs({input});
    outputs.declare(output, "-o", image::writableImageExtensions());
    if (outDepth && image::closestDepth(output, *outDepth) != *outDepth) {
      throw makeError(output, ": --depth ", depth, ": the format of '",
                      std::filesystem::path(output).extension().string(),
                      "' cannot store it; use .png or .tif for 16, .tif or .exr for float");
    }

    image::ImageInfo info;
    image::Image img = image::loadImage(input, &info);
    if (info.alpha_only) throw makeError(input, ": the image has only an alpha channel; expected grey or colour");
    texsynth::EnhanceReport report;
    const image::Image result = texsynth::enhanceContrast(std::move(img), options, &report, input);
    if (!outDepth) {
      outDepth = image::closestDepth(output, info.depth == image::PixelDepth::UInt8    ? image::PixelDepth::UInt8
                                             : info.depth == image::PixelDepth::UInt16 ? image::PixelDepth::UInt16
                                                                                       : image::PixelDepth::Float);
    }
    outputs.stage(output, image::encodeImage(result, output, *outDepth, {.smallest = smallest}));
    outputs.commit();
    std::fprintf(stderr, "%s: mapped %g:%g to %g:%g%s; %.2f%% of values at or below A, %.2f%% above B\n", input.c_str(),
                 report.input_range.low, report.input_range.high, c, d, options.input_range ? "" : " (percentiles)",
                 100.0 * report.clipped_low, 100.0 * report.clipped_high);
  });
}
