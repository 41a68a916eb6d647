// A bench program's tables (CSV, Markdown): text gathered in memory, staged into hidden
// temporaries (checked writes, sync) when the program is done with each, and renamed over
// their targets all together when the program ends with status 0. A full disk or a file
// size limit on the last table, or a run that fails half way, leaves every table of an
// earlier run as it was. A write that fails ends the program with one line naming the file.
#pragma once

#include <stdlib.h>  // on_exit (glibc)

#include <cstdio>
#include <exception>
#include <filesystem>
#include <optional>
#include <sstream>

#include "shanshui/core/atomic_output.h"

namespace shanshui::bench {

//! The outputs of this bench run, committed together by on_exit when the status is 0, and
//! otherwise removed with the run's temporaries.
class RunOutputs {
 public:
  static RunOutputs& get() {
    static RunOutputs* run = new RunOutputs;  // kept through exit, for the handler
    return *run;
  }
  void stage(const std::filesystem::path& target, const std::string& text) {
    set_->declare(target, target.filename().string());
    set_->stage(target, text);
  }
  //! Removes what was staged (before an exit that skips the handler).
  void discard() { set_.reset(); }
  //! Ends the process with `status` as exit() would for the run's outputs (committed when 0,
  //! removed otherwise) but without the process's other exit handlers and destructors: a
  //! forked child of a process with threads must not run them (Mesa's, for one, waits for
  //! its worker threads, which the child does not have).
  [[noreturn]] void endNow(int status) {
    atExit(status, this);
    std::_Exit(status);
  }

 private:
  RunOutputs() : set_(std::in_place) {
    installTempFileCleanup();
    ::on_exit(&RunOutputs::atExit, this);
  }
  static void atExit(int status, void* self) {
    auto& set = static_cast<RunOutputs*>(self)->set_;
    if (!set) return;
    if (status == 0) {
      try {
        set->commit();
      } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        set.reset();
        std::_Exit(1);
      }
    }
    set.reset();
  }
  std::optional<OutputSet> set_;
};

class OutputFile : public std::ostringstream {
 public:
  explicit OutputFile(std::filesystem::path target) : target_(std::move(target)) { checkOutputPath(target_); }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  //! Stages the text now (also done on destruction, unless an exception is unwinding); it
  //! replaces the target with the run's other tables when the program ends well.
  void commit() {
    if (committed_) return;
    committed_ = true;
    RunOutputs::get().stage(target_, str());
  }
  // A failed write ends the program here with one line naming the file and exit code 1;
  // nothing of this run is written.
  ~OutputFile() override {
    if (std::uncaught_exceptions() > 0) return;
    try {
      commit();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "error: %s\n", e.what());
      RunOutputs::get().discard();
      std::_Exit(1);
    }
  }

 private:
  std::filesystem::path target_;
  bool committed_ = false;
};

}  // namespace shanshui::bench
