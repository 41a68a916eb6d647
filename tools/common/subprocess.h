// Running another shanshui program from a driver (shanshui-demo, shanshui-bench): its
// stdout and stderr go to a log file, optionally echoed line by line with a prefix.
#pragma once

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "shanshui/core/error.h"

namespace shanshui::tools {

//! The string as one POSIX shell word.
inline std::string shellQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct ProgramRun {
  bool ok = false;        //!< exited normally with status 0
  int status = 0;         //!< the raw wait status
  std::string last_line;  //!< the last non-empty line it printed
};

//! Longest single argument and all arguments together that runProgram() passes (Linux
//! refuses one argument over 128 KiB and lets the whole command line use a quarter of the stack limit).
constexpr std::size_t kMaxArgumentBytes = 128 * 1024 - 1;
constexpr std::size_t kMaxArgumentsBytes = 1024 * 1024;

//! Runs `program args...` (no shell) with both streams captured into `log`
//! (overwritten). With `echo_prefix` non-empty, each line is also printed to stderr as it
//! arrives, after the prefix. Throws an Error when the log cannot be written, the arguments
//! are too long, or the program cannot be started; a failing program is reported in the result.
inline ProgramRun runProgram(const std::filesystem::path& program, const std::vector<std::string>& args,
                             const std::filesystem::path& log, const std::string& echo_prefix = {}) {
  std::size_t total = program.string().size() + 1;
  for (const std::string& a : args) {
    if (a.size() > kMaxArgumentBytes) {
      throw makeError("an argument of ", a.size(), " bytes is longer than the limit of ", kMaxArgumentBytes,
                      " (it begins '", a.substr(0, 40), "')");
    }
    total += a.size() + 1;
  }
  if (total > kMaxArgumentsBytes) {
    throw makeError("the arguments take ", total, " bytes, more than the limit of ", kMaxArgumentsBytes);
  }
  std::ofstream out(log);
  if (!out) throw makeError(log.string(), ": cannot write the log");
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw makeError(program.string(), ": cannot start: ", std::strerror(errno));
  std::vector<std::string> words{program.string()};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 1);
  posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (spawned != 0) {
    ::close(fds[0]);
    throw makeError(program.string(), ": cannot start: ", std::strerror(spawned));
  }
  FILE* pipe = ::fdopen(fds[0], "r");
  ProgramRun r;
  std::string line;
  auto finish = [&] {
    out << line << '\n';
    out.flush();
    if (!echo_prefix.empty()) std::fprintf(stderr, "%s%s\n", echo_prefix.c_str(), line.c_str());
    if (!line.empty()) r.last_line = line;
    line.clear();
  };
  for (int c; (c = std::fgetc(pipe)) != EOF;) {
    if (c == '\n' || c == '\r')
      finish();
    else
      line += static_cast<char>(c);
  }
  if (!line.empty()) finish();
  std::fclose(pipe);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.status = status;
  r.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return r;
}

}  // namespace shanshui::tools
