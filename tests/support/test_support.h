// Shared helpers for shanshui's tests: where the inputs are, scratch directories,
// running a program, and meshes with known geometry.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace shanshui::test {

namespace fs = std::filesystem;

inline fs::path sourceDir() {
  return SHANSHUI_SOURCE_DIR;
}
inline fs::path binDir() {
  return SHANSHUI_BIN_DIR;
}
//! The real DEMs and scans beside the repository (../shared/data unless configured otherwise).
//! The environment variable SHANSHUI_DATA_DIR overrides it at run time: `.ci/run` points it at
//! an empty folder to prove that every test passes or skips on a bare clone.
inline fs::path sharedData() {
  if (const char* dir = std::getenv("SHANSHUI_DATA_DIR"); dir && *dir) return dir;
  return SHANSHUI_DATA_DIR;
}
inline fs::path cgalMeshes() {
  return SHANSHUI_TEST_MESH_DIR;
}

//! Every texture scan in the shared data (sorted); without the shared data, the scan the
//! repository ships (samples/textures/rain_strokes_scan.png), so a bare clone still tests.
inline std::vector<fs::path> textureScans() {
  std::vector<fs::path> files;
  const fs::path dir = sharedData() / "textures";
  if (fs::is_directory(dir)) {
    for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) files.push_back(sourceDir() / "samples/textures/rain_strokes_scan.png");
  return files;
}

//! Skips the calling test when an input is missing, saying which.
#define SHANSHUI_REQUIRE_FILE(path)                                                 \
  do {                                                                              \
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "missing input " << (path); \
  } while (false)

//! A fresh directory per test, removed at the end.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("shanshui_" + std::string(info ? info->test_suite_name() : "t") + "_" +
                                         std::string(info ? info->name() : "t") + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() { fs::remove_all(path_); }
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  //!< stdout and stderr together
};

//! Runs a shell command, capturing its output.
inline CommandResult run(const std::string& command) {
  CommandResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.output.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

inline std::string quote(const fs::path& p) {
  return "'" + p.string() + "'";
}

//! Expects `call` to throw an exception whose one-line message contains both `file` and
//! `what`.
template <typename Call>
void expectErrorNaming(Call&& call, const std::string& file, const std::string& what) {
  try {
    call();
    ADD_FAILURE() << "no error for " << file;
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
  }
}

}  // namespace shanshui::test
