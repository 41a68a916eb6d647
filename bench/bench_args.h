// The command line every error-against-run-time bench program shares: --out DIR, --quick,
// and a few value options of its own. Anything else prints the usage and exits with 2. An
// error thrown anywhere in a bench program ends it with one line and exit code 1.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <string>

namespace shanshui::bench {

struct BenchArgs {
  std::filesystem::path out = ".";
  bool quick = false;
  std::map<std::string, std::string> values;  //!< the program's own options that were given

  std::string text(const std::string& flag, const std::string& fallback) const {
    const auto it = values.find(flag);
    return it == values.end() ? fallback : it->second;
  }
  //! The option as a positive integer; anything else is a one-line error and exit code 2.
  int integer(const std::string& flag, int fallback) const {
    const auto it = values.find(flag);
    if (it == values.end()) return fallback;
    char* end = nullptr;
    const long v = std::strtol(it->second.c_str(), &end, 10);
    if (it->second.empty() || *end != '\0' || v <= 0 || v > 1 << 20) {
      std::fprintf(stderr, "error: %s '%s': expected a positive integer\n", flag.c_str(), it->second.c_str());
      std::exit(2);
    }
    return static_cast<int>(v);
  }
};

//! Installed by every program that includes this header: an uncaught exception prints its
//! message in one line (instead of "terminate called after ...") and exits with 1.
[[noreturn]] inline void reportUncaught() {
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::exception& x) {
      std::fprintf(stderr, "error: %s\n", x.what());
    } catch (...) {
      std::fprintf(stderr, "error: unknown exception\n");
    }
  }
  std::_Exit(1);
}
inline const std::terminate_handler kPreviousTerminate = std::set_terminate(reportUncaught);

inline BenchArgs parseBenchArgs(int argc, char** argv, const char* usage, std::initializer_list<const char*> own = {}) {
  BenchArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    bool known = false;
    for (const char* o : own) known = known || flag == o;
    if (flag == "--quick") {
      a.quick = true;
    } else if ((flag == "--out" || known) && i + 1 < argc) {
      if (flag == "--out")
        a.out = argv[++i];
      else
        a.values[flag] = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s\n", usage);
      std::exit(2);
    }
  }
  return a;
}

}  // namespace shanshui::bench
