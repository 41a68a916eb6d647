// A bench program's table (CSV, Markdown): text gathered in memory and written to its target
// atomically when the program is done with it (checked writes, sync, rename), so a full
// disk or a file size limit leaves the table of an earlier run as it was. A write that fails
// ends the program with one line naming the file.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <sstream>

#include "shanshui/core/atomic_output.h"

namespace shanshui::bench {

class OutputFile : public std::ostringstream {
 public:
  explicit OutputFile(std::filesystem::path target) : target_(std::move(target)) { checkOutputPath(target_); }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  //! Writes the text now (also done on destruction, unless an exception is unwinding).
  void commit() {
    if (committed_) return;
    committed_ = true;
    writeFileAtomically(target_, str());
  }
  // A failed write ends the program here with one line naming the file and exit code 1;
  // nothing after it is written.
  ~OutputFile() override {
    if (std::uncaught_exceptions() > 0) return;
    try {
      commit();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      std::_Exit(1);
    }
  }

 private:
  std::filesystem::path target_;
  bool committed_ = false;
};

}  // namespace shanshui::bench
