// Running another shanshui program from a driver (shanshui-demo, shanshui-bench): its
// stdout and stderr go to a log file, optionally echoed line by line with a prefix.
#pragma once

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
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
  bool ok = false;         //!< exited normally with status 0
  bool timed_out = false;  //!< stopped at the time limit (ok is false)
  int status = 0;          //!< the raw wait status
  std::string last_line;   //!< the last non-empty line it printed
};

//! While it lives, SIGINT, SIGTERM and SIGHUP sent to this process are passed on to the
//! process group given to forwardTo() (kept until then); when it ends, the first of them is
//! raised again here with its previous action, so the driver ends as it would have without
//! a program running.
class ForwardedSignals {
 public:
  ForwardedSignals() {
    target() = 0;
    received() = 0;
    struct sigaction forward = {};
    forward.sa_handler = [](int sig) {
      if (received() == 0) received() = sig;
      if (target() > 0) ::kill(-target(), sig);
    };
    ::sigemptyset(&forward.sa_mask);
    for (std::size_t i = 0; i < kSignals.size(); ++i) {
      // A signal this process ignores (started under nohup, or in the background) stays ignored.
      ::sigaction(kSignals[i], nullptr, &previous_[i]);
      if (previous_[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &forward, nullptr);
    }
  }
  ~ForwardedSignals() {
    for (std::size_t i = 0; i < kSignals.size(); ++i) ::sigaction(kSignals[i], &previous_[i], nullptr);
    target() = 0;
    if (const int sig = received(); sig != 0) ::raise(sig);
  }
  void forwardTo(pid_t group) {
    target() = group;
    if (const int sig = received(); sig != 0) ::kill(-group, sig);  // arrived while it started
  }
  ForwardedSignals(const ForwardedSignals&) = delete;
  ForwardedSignals& operator=(const ForwardedSignals&) = delete;

 private:
  static constexpr std::array<int, 3> kSignals{SIGINT, SIGTERM, SIGHUP};
  static volatile pid_t& target() {
    static volatile pid_t t = 0;
    return t;
  }
  static volatile std::sig_atomic_t& received() {
    static volatile std::sig_atomic_t r = 0;
    return r;
  }
  std::array<struct sigaction, 3> previous_{};
};

//! Longest single argument and all arguments together that runProgram() passes (Linux
//! refuses one argument over 128 KiB and lets the whole command line use a quarter of the stack limit).
constexpr std::size_t kMaxArgumentBytes = 128 * 1024 - 1;
constexpr std::size_t kMaxArgumentsBytes = 1024 * 1024;

//! Runs `program args...` (no shell) with both streams captured into `log`
//! (overwritten). With `echo_prefix` non-empty, each line is also printed to stderr as it
//! arrives, after the prefix. With `time_limit_s` above 0 a program still running after that
//! long is stopped with everything it started (it runs in a process group of its own):
//! SIGTERM, then SIGKILL two seconds later. Throws an Error when the log cannot be written,
//! the arguments are too long, or the program cannot be started; a failing or stopped
//! program is reported in the result.
inline ProgramRun runProgram(const std::filesystem::path& program, const std::vector<std::string>& args,
                             const std::filesystem::path& log, const std::string& echo_prefix = {},
                             double time_limit_s = 0.0) {
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
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);  // its own group: stopped as a whole
  posix_spawnattr_setpgroup(&attributes, 0);
  // A terminal's Ctrl-C (and a TERM or HUP sent to this driver) reaches the program's group
  // too, which is not the terminal's; this driver then ends as the signal would have ended it.
  ForwardedSignals forwarding;
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, program.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  ::close(fds[1]);
  if (spawned != 0) {
    ::close(fds[0]);
    throw makeError(program.string(), ": cannot start: ", std::strerror(spawned));
  }
  forwarding.forwardTo(pid);
  ProgramRun r;
  std::string line;
  auto finish = [&] {
    out << line << '\n';
    out.flush();
    if (!echo_prefix.empty()) std::fprintf(stderr, "%s%s\n", echo_prefix.c_str(), line.c_str());
    if (!line.empty()) r.last_line = line;
    line.clear();
  };
  // Read until every writer of the pipe has closed it (the program and whatever it started),
  // or the time limit: then SIGTERM to the group, SIGKILL two seconds later, and after that
  // at most two more seconds for the pipe to close.
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                           std::chrono::duration<double>(std::max(time_limit_s, 0.0)));
  std::optional<Clock::time_point> next_step;  //!< when the next signal is due after the limit
  int steps_taken = 0;                         //!< 1: TERM sent; 2: KILL sent; 3: given up on the pipe
  char buffer[4096];
  while (steps_taken < 3) {
    int wait_ms = -1;
    if (time_limit_s > 0.0) {
      const auto now = Clock::now();
      if (steps_taken == 0 && now >= deadline) {
        r.timed_out = true;
        ::kill(-pid, SIGTERM);
        steps_taken = 1;
        next_step = now + std::chrono::seconds(2);
      } else if (next_step && now >= *next_step) {
        if (steps_taken == 1) ::kill(-pid, SIGKILL);
        ++steps_taken;
        next_step = now + std::chrono::seconds(2);
        if (steps_taken == 3) break;
      }
      const auto until = next_step ? *next_step : deadline;
      wait_ms = static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(until - now).count()) + 1;
    }
    struct pollfd p = {fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, wait_ms);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;  // the time to check the limit, or a signal
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    for (ssize_t i = 0; i < n; ++i) {
      if (buffer[i] == '\n' || buffer[i] == '\r')
        finish();
      else
        line += buffer[i];
    }
  }
  if (!line.empty()) finish();
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.status = status;
  r.ok = !r.timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return r;
}

}  // namespace shanshui::tools
