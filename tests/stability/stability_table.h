// The stability suite's table: one row per case, shared by the suite's source files and
// written by the suite's environment (stability_test.cpp) when the process ends.
#pragma once

#include <sstream>
#include <string>
#include <vector>

namespace shanshui {

struct Row {
  std::string stage, name, outcome;
};

inline std::vector<Row>& table() {
  static std::vector<Row> rows;
  return rows;
}

//! The kind of an outcome, from its leading words: "clear error" and "finite result" are
//! handled; "CRASH", "HANG" and "PARTIAL OUTPUT" are the failures the summary counts.
inline std::string outcomeKind(const std::string& outcome) {
  for (const char* kind : {"clear error", "finite result", "CRASH", "HANG", "PARTIAL OUTPUT"}) {
    if (outcome.rfind(kind, 0) == 0) return kind;
  }
  return "other";
}

// The lines of a program's output that report an error (progress lines may come first).
inline std::vector<std::string> errorLines(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string line; std::getline(in, line);)
    if (line.find("error") != std::string::npos) out.push_back(line);
  return out;
}

}  // namespace shanshui
