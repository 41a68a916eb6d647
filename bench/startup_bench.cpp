// Start-up cost of every tool (`--help` wall time, fork to exit) and shanshui-enhance on a
// 4096² 16-bit PNG with fast (default) and --smallest compression, beside the same stretch
// done with OpenCV in this process (imread, 1 %/99 % percentiles from a 65536-bin
// histogram, convertTo, imwrite with OpenCV's default PNG settings): no process start, so
// the ratio flatters OpenCV slightly. Side by side in one run; real time.
//   build/bin/bench_startup --benchmark_min_time=1
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "shanshui/image/image_io.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;

fs::path binDir() {
  return fs::canonical("/proc/self/exe").parent_path();
}

// Runs the program with stdout and stderr discarded; aborts the benchmark on failure.
void runQuiet(benchmark::State& state, const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  if (rc != 0 || waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    state.SkipWithError(("failed: " + args[0]).c_str());
  }
}

void BM_Help(benchmark::State& state, const char* tool) {
  const std::string exe = (binDir() / tool).string();
  for (auto _ : state) runQuiet(state, {exe, "--help"});
}

// A 4096 x 4096 16-bit grey scan-like image (noise over a ramp), made once.
const fs::path& bigPng() {
  static const fs::path path = [] {
    const fs::path p = fs::temp_directory_path() / ("shanshui_bench_startup_" + std::to_string(getpid()) + ".png");
    shanshui::image::Image img(4096, 4096, 1);
    std::mt19937 rng(1);
    std::normal_distribution<float> noise(0.0f, 0.05f);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        img.at(x, y, 0) = std::clamp(0.3f + 0.4f * x / img.width + noise(rng), 0.0f, 1.0f);
    shanshui::image::saveImage(img, p, shanshui::image::PixelDepth::UInt16);
    return p;
  }();
  return path;
}

void BM_Enhance4096(benchmark::State& state, bool smallest) {
  const std::string exe = (binDir() / "shanshui-enhance").string();
  const fs::path out = fs::temp_directory_path() / ("shanshui_bench_startup_out_" + std::to_string(getpid()) + ".png");
  std::vector<std::string> args = {exe, bigPng().string(), "-o", out.string()};
  if (smallest) args.push_back("--smallest");
  for (auto _ : state) runQuiet(state, args);
  state.counters["bytes_out"] = static_cast<double>(fs::exists(out) ? fs::file_size(out) : 0);
  fs::remove(out);
}

// The baseline: the same percentile stretch in a few lines of OpenCV.
void BM_OpenCvStretch4096(benchmark::State& state) {
  const fs::path out = fs::temp_directory_path() / ("shanshui_bench_startup_cv_" + std::to_string(getpid()) + ".png");
  for (auto _ : state) {
    const cv::Mat in = cv::imread(bigPng().string(), cv::IMREAD_UNCHANGED);
    const int channels[] = {0};
    const int bins[] = {65536};
    const float range[] = {0.0f, 65536.0f};
    const float* ranges[] = {range};
    cv::Mat hist;
    cv::calcHist(&in, 1, channels, cv::Mat(), hist, 1, bins, ranges);
    const double total = static_cast<double>(in.total());
    double sum = 0;
    int low = -1, high = -1;
    for (int b = 0; b < 65536 && high < 0; ++b) {
      sum += hist.at<float>(b);
      if (low < 0 && sum >= 0.01 * total) low = b;
      if (sum >= 0.99 * total) high = b;
    }
    cv::Mat stretched;
    const double scale = 65535.0 / std::max(1, high - low);
    in.convertTo(stretched, CV_16U, scale, -low * scale);
    cv::imwrite(out.string(), stretched);
  }
  state.counters["bytes_out"] = static_cast<double>(fs::exists(out) ? fs::file_size(out) : 0);
  fs::remove(out);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Help, enhance, "shanshui-enhance")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Help, quilt, "shanshui-quilt")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Help, terrain, "shanshui-terrain")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Help, repair, "shanshui-repair")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Help, param, "shanshui-param")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Help, render, "shanshui-render")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Enhance4096, fast, false)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK_CAPTURE(BM_Enhance4096, smallest, true)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_OpenCvStretch4096)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  std::error_code ec;
  fs::remove(bigPng(), ec);
  return 0;
}
