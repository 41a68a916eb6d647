// Running another shanshui program from a driver (shanshui-demo, shanshui-bench): its
// stdout and stderr go to a log file, optionally echoed line by line with a prefix.
#pragma once

#include <sys/wait.h>

#include <cstdio>
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
  bool ok = false;       //!< exited normally with status 0
  int status = 0;        //!< the raw wait status
  std::string last_line; //!< the last non-empty line it printed
};

//! Runs `program args...` through the shell with both streams captured into `log`
//! (overwritten). With `echo_prefix` non-empty, each line is also printed to stderr as it
//! arrives, after the prefix. Throws an Error only when the log cannot be written or the
//! program cannot be started; a failing program is reported in the result.
inline ProgramRun runProgram(const std::filesystem::path& program, const std::vector<std::string>& args,
                             const std::filesystem::path& log, const std::string& echo_prefix = {}) {
  std::ofstream out(log);
  if (!out) throw makeError(log.string(), ": cannot write the log");
  std::string command = shellQuote(program.string());
  for (const std::string& a : args) command += " " + shellQuote(a);
  command += " 2>&1 </dev/null";
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw makeError(program.string(), ": cannot start");
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
    if (c == '\n' || c == '\r') finish();
    else line += static_cast<char>(c);
  }
  if (!line.empty()) finish();
  r.status = ::pclose(pipe);
  r.ok = r.status != -1 && WIFEXITED(r.status) && WEXITSTATUS(r.status) == 0;
  return r;
}

}  // namespace shanshui::tools
