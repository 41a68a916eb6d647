// Where the bench programs find their real inputs: the data beside the repository
// (../shared/data unless configured otherwise, or the environment variable SHANSHUI_DATA_DIR
// at run time), and the repository's own samples where that data is absent.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace shanshui::bench {

inline std::filesystem::path dataDir() {
  if (const char* dir = std::getenv("SHANSHUI_DATA_DIR"); dir && *dir) return dir;
  return SHANSHUI_DATA_DIR;
}

//! The texture scans of the shared data, sorted; without them the scan the repository ships.
inline std::vector<std::filesystem::path> textureScans() {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path dir = dataDir() / "textures";
  if (std::filesystem::is_directory(dir)) {
    for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty())
    files.push_back(std::filesystem::path(SHANSHUI_SOURCE_DIR) / "samples/textures/rain_strokes_scan.png");
  return files;
}

}  // namespace shanshui::bench
