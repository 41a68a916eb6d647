// The common output of the error-against-run-time benches, which shanshui-bench plots: one
// CSV row per measured point, `plot,y_label,series,joined,ms,error` — run time in
// milliseconds against an error measured on an input with a known answer. Points of a
// series with joined = 1 are a sweep of one knob and are drawn joined in order; otherwise
// they are separate inputs and drawn as markers only.
#pragma once

#include <filesystem>
#include <string>

#include "bench_output.h"

namespace shanshui::bench {

class TradeoffPoints {
 public:
  explicit TradeoffPoints(const std::filesystem::path& csv) : out_(csv) {
    out_ << "plot,y_label,series,joined,ms,error\n";
    out_.precision(9);
  }

  void add(const std::string& plot, const std::string& y_label, const std::string& series, bool joined, double ms,
           double error) {
    out_ << quoted(plot) << ',' << quoted(y_label) << ',' << quoted(series) << ',' << (joined ? 1 : 0) << ',' << ms
         << ',' << error << '\n';
  }

 private:
  static std::string quoted(const std::string& s) {
    std::string q = "\"";
    for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
    return q + '"';
  }
  OutputFile out_;
};

}  // namespace shanshui::bench
