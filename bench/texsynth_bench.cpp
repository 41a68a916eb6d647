// Speed of the texture tools (issue targets: 1024² grey output from a 192² sample with
// block 48 / overlap 8 in <= 1.5 s; FFT search >= 10x faster than exhaustive; enhancement
// of a 4096² 16-bit image in <= 0.5 s). Compare rows of one run with each other: this
// machine is shared and noisy.
#include <filesystem>
#include <random>

#include <benchmark/benchmark.h>

#include "bench_data.h"
#include "shanshui/image/convert.h"
#include "shanshui/image/image_io.h"
#include "shanshui/texsynth/enhance.h"
#include "shanshui/texsynth/quilting.h"

namespace {

using namespace shanshui;

// efros_t1.png (192×192, bricks) as grey; a seeded noise image if the data is absent.
const image::Image& greySample() {
  static const image::Image sample = [] {
    const std::filesystem::path f = shanshui::bench::dataDir() / "textures/efros_t1.png";
    if (std::filesystem::exists(f)) return image::toGrey(image::loadImage(f));
    image::Image img(192, 192, 1);
    std::mt19937 rng(1);
    for (float& v : img.pixels) v = static_cast<float>(rng() % 256) / 255.0f;
    return img;
  }();
  return sample;
}

void BM_Quilt1024Grey(benchmark::State& state) {
  texsynth::QuiltOptions o;
  o.width = o.height = 1024;
  o.block = 48;
  o.overlap = 8;
  o.threads = static_cast<int>(state.range(0));
  o.seam = static_cast<texsynth::SeamMode>(state.range(1));
  for (auto _ : state) benchmark::DoNotOptimize(texsynth::quilt(greySample(), o));
  state.SetLabel(std::string("seam ") + texsynth::seamModeName(o.seam));
}
BENCHMARK(BM_Quilt1024Grey)
    ->Args({0, static_cast<int>(texsynth::SeamMode::Cut)})
    ->Args({1, static_cast<int>(texsynth::SeamMode::Cut)})
    ->Args({0, static_cast<int>(texsynth::SeamMode::GraphCut)})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One block's overlap search (L-shaped overlap, B = 48, O = 8) over the 192² sample.
void BM_BlockSearch(benchmark::State& state) {
  const image::Image& sample = greySample();
  const int b = 48, o = 8;
  const texsynth::OverlapSearch search(sample, b);
  image::Image patch(b, b, 1);
  for (int y = 0; y < b; ++y)
    for (int x = 0; x < b; ++x) patch.at(x, y) = sample.at(x + 30, y + 50);
  cv::Mat mask = cv::Mat::zeros(b, b, CV_8U);
  mask.colRange(0, o).setTo(1);
  mask.rowRange(0, o).setTo(1);
  const auto mode = static_cast<texsynth::SearchMode>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(search.errors(patch, mask, mode));
  state.SetLabel(texsynth::searchModeName(mode));
}
BENCHMARK(BM_BlockSearch)
    ->Arg(static_cast<int>(texsynth::SearchMode::Fft))
    ->Arg(static_cast<int>(texsynth::SearchMode::Exhaustive))
    ->Unit(benchmark::kMillisecond);

void BM_Enhance4096Grey16(benchmark::State& state) {
  image::Image img(4096, 4096, 1);
  std::mt19937 rng(3);
  for (float& v : img.pixels) v = static_cast<float>(rng() % 40000 + 10000) / 65535.0f;
  for (auto _ : state) benchmark::DoNotOptimize(texsynth::enhanceContrast(img, {}));
}
BENCHMARK(BM_Enhance4096Grey16)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
