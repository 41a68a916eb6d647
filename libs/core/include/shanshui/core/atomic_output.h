// Writing outputs so that a failure never leaves a half-finished file over a good one.
//
// Every output goes first into a hidden temporary next to its target
// (".NAME.tmpPID_N.ext"), written with checked system calls and synced, then renamed over
// the target. The temporaries of a process are removed when it fails, when it is stopped
// by SIGINT, SIGTERM or SIGHUP, and (for one that was killed outright) by the next run
// that writes the same target. A tool with several outputs declares them all in an
// OutputSet before doing any work and commits them together at the end.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "shanshui/core/input.h"  // the input gate, used with every OutputSet

namespace shanshui {

//! Writes `bytes` to `target` atomically. Every write is checked (a full disk, a file size
//! limit or an I/O error throws an Error naming `target` and the system's reason), the data
//! are synced before the rename, and on failure `target` is untouched and no temporary is left.
void writeFileAtomically(const std::filesystem::path& target, std::string_view bytes);

//! Calls write(tmp) with a temporary path next to `target` (same directory, same
//! extension so format-sniffing writers still work), then renames it over `target`.
//! If write throws, the temporary file is removed and `target` is left untouched. The
//! writer must check its own writes: prefer writeFileAtomically() with bytes in memory.
void writeAtomically(const std::filesystem::path& target,
                     const std::function<void(const std::filesystem::path& tmp)>& write);

//! Throws the Error a write to `target` would meet (missing or read-only directory, target
//! is a directory or read-only), so a tool can refuse before a long computation.
void checkOutputPath(const std::filesystem::path& target);

//! Installs SIGINT/SIGTERM/SIGHUP handlers that remove this process's live temporaries and
//! then end the process as the signal would have. Idempotent; every tool calls it.
void installTempFileCleanup();

//! Under an address-space limit (ulimit -v) a driver may crash instead of reporting that
//! memory ran out: then a SIGSEGV, SIGBUS or SIGABRT removes this process's temporaries, prints one
//! line naming `component` ("the GL driver") and the limit, and exits 1. Without a limit it
//! does nothing, so a crash elsewhere stays a crash to be found.
void guardCrashesUnderMemoryLimit(std::string_view component);

//! Whether memory ran out in this process under an address-space limit: operator new failed
//! after guardCrashesUnderMemoryLimit, or a driver reported it (noteMemoryRanOut, which does
//! nothing without a limit: a GPU's out-of-memory error leaves its driver working). A GL driver
//! that ran out may hang in its next call (llvmpipe did, deleting a texture while the error
//! unwound), so the GL wrappers stop calling it and the tool ends without exit handlers.
bool memoryRanOut();
void noteMemoryRanOut();

//! Removes temporaries of `target` left by processes that no longer run (killed outright).
//! Called by every write; public for tests.
void sweepStaleTemporaries(const std::filesystem::path& target);

//! The hidden temporary name for `target` of process `pid`, attempt `n`.
std::filesystem::path temporaryPath(const std::filesystem::path& target, long pid, unsigned n);

//! An exclusive lock held for a whole run of a program whose outputs are written stage by
//! stage (the demo): a second run into the same place waits until the first has ended, saying
//! once on stderr what it waits for, so two runs never interleave their stages. The lock is
//! on `file` (created if missing, left in place: removing a lock file races with the next
//! run), not on a directory, so the programs a run starts still commit into it.
class RunLock {
 public:
  //! `who` names the program in the waiting message ("shanshui-demo").
  RunLock(const std::filesystem::path& file, std::string_view who);
  ~RunLock();
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;
  //! Whether this run had to wait for another one.
  bool waited() const { return waited_; }

 private:
  int fd_ = -1;
  bool waited_ = false;
};

//! The outputs of one run, declared before any work and committed together at the end:
//!   OutputSet out({input});
//!   out.declare(output, "-o", {".png", ".jpg"});
//!   out.declare(report, "--report", {".json"});
//!   ... compute ...
//!   out.stage(output, bytes); out.stage(report, json);   // into temporaries
//!   out.commit();                                         // renames, all or none written
//! declare() checks the directory is writable, the extension known, and the path distinct
//! from every other output and every input. Staged temporaries that are not committed are
//! removed by the destructor (and by the signal handlers).
class OutputSet {
 public:
  explicit OutputSet(std::vector<std::filesystem::path> inputs = {});
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  //! `what` names the option in errors ("--report"); `extensions` lists the accepted ones in
  //! lower case with the dot (empty: any).
  void declare(const std::filesystem::path& target, std::string_view what,
               const std::vector<std::string>& extensions = {});
  //! Adds an input that no output may overwrite.
  void addInput(const std::filesystem::path& input);

  //! Writes the bytes into a hidden temporary beside `target` (checked, synced); the
  //! target is untouched until commit().
  void stage(const std::filesystem::path& target, std::string_view bytes);
  //! Renames every staged temporary over its target, in declaration order, holding a lock on
  //! their directories: a second run committing into them waits, so outputs never mix.
  void commit();

 private:
  struct Entry {
    std::filesystem::path target;
    std::filesystem::path key;  //!< weakly canonical, to compare paths
    std::string what;
    std::filesystem::path staged;
    void* slot;  //!< the staged temporary's registration for removal on a signal
  };
  Entry& find(const std::filesystem::path& target);
  std::vector<std::filesystem::path> inputs_;
  std::vector<Entry> entries_;
  std::map<std::filesystem::path, std::size_t> byKey_;                                //!< canonical path -> entry
  std::map<std::pair<unsigned long long, unsigned long long>, std::size_t> byInode_;  //!< existing file -> entry
};

}  // namespace shanshui
