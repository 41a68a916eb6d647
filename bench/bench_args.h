// The command line every error-against-run-time bench program shares: --out DIR, --quick,
// and a few value options of its own. Anything else prints the usage and exits with 2.
#pragma once

#include <cstdio>
#include <cstdlib>
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
  int integer(const std::string& flag, int fallback) const {
    const auto it = values.find(flag);
    return it == values.end() ? fallback : std::stoi(it->second);
  }
};

inline BenchArgs parseBenchArgs(int argc, char** argv, const char* usage, std::initializer_list<const char*> own = {}) {
  BenchArgs a;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    bool known = false;
    for (const char* o : own) known = known || flag == o;
    if (flag == "--quick") {
      a.quick = true;
    } else if ((flag == "--out" || known) && i + 1 < argc) {
      if (flag == "--out") a.out = argv[++i];
      else a.values[flag] = argv[++i];
    } else {
      std::fprintf(stderr, "usage: %s\n", usage);
      std::exit(2);
    }
  }
  return a;
}

}  // namespace shanshui::bench
