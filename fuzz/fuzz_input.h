// Shared by the fuzz targets: each parser of shanshui reads files, so a fuzz input is
// written to a scratch file with the parser's extension first. An Error is the clear
// refusal every bad input must get; anything else (another exception, a crash, a
// sanitizer report, a hang) is a finding.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "shanshui/core/error.h"

namespace shanshui::fuzz {

//! A scratch file holding the input, removed when it goes out of scope.
class ScratchFile {
 public:
  ScratchFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
    path_ = std::filesystem::temp_directory_path() / ("shanshui_fuzz_" + std::to_string(::getpid()) + extension);
    std::ofstream(path_, std::ios::binary)
        .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  ~ScratchFile() {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

//! Runs `parse`; an Error is an accepted outcome, anything else escapes to the fuzzer.
template <typename Parse>
void expectParsedOrRefused(Parse&& parse) {
  try {
    parse();
  } catch (const Error&) {
  }
}

}  // namespace shanshui::fuzz
