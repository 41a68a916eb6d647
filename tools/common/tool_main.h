// The shared shape of every shanshui command-line program: parse with CLI11, run, and turn
// any error into one line on stderr and a non-zero exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <functional>

#include "shanshui/core/error.h"

namespace shanshui::tools {

//! Runs `body` after parsing; returns the process exit code (0 ok, 1 error, CLI11's code
//! for usage errors, 0 for --help).
inline int runTool(CLI::App& app, int argc, char** argv, const std::function<void()>& body) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    body();
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", app.get_name().c_str(), e.what());
    return 1;
  }
}

}  // namespace shanshui::tools
