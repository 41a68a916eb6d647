// The shared shape of every shanshui command-line program: parse with CLI11, run, and turn
// any error into one line on stderr and a non-zero exit code.
#pragma once

#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <string>
#include <system_error>

#include <CLI/CLI.hpp>

#include "batch.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"

namespace shanshui::tools {

//! CLI11 check for an integer option: a whole number in [min, max] (defaults: at least `min`,
//! any that fits 64 bits). Its message names the value and the range, in one line.
inline CLI::Validator integerIn(long long min, unsigned long long max = ~0ULL) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        const char* b = text.data();
        const char* e = b + text.size();
        if (b != e && *b == '-') {
          long long v = 0;
          const auto [p, ec] = std::from_chars(b, e, v);
          if (ec != std::errc() || p != e) return "'" + text + "' is not a whole number";
          if (v < min) return text + " is out of range; expected at least " + std::to_string(min);
          return {};
        }
        unsigned long long v = 0;
        const auto [p, ec] = std::from_chars(b, e, v);
        if (ec == std::errc::result_out_of_range)
          return text + " is out of range; expected at most " + std::to_string(max);
        if (ec != std::errc() || p != e) return "'" + text + "' is not a whole number";
        if (min > 0 && v < static_cast<unsigned long long>(min)) {
          return text + " is out of range; expected at least " + std::to_string(min);
        }
        if (v > max) return text + " is out of range; expected at most " + std::to_string(max);
        return {};
      },
      max == ~0ULL ? ">=" + std::to_string(min) : "[" + std::to_string(min) + ", " + std::to_string(max) + "]");
}

//! Once memory ran out under an address-space limit a driver's threads or exit handlers may
//! never finish (memoryRanOut): the error is written, the temporaries are gone with the
//! unwinding, so the process ends here, without them.
inline void endIfMemoryRanOut() {
  if (!memoryRanOut()) return;
  std::fflush(nullptr);
  ::_exit(1);
}

//! Runs `body` after parsing; returns the process exit code (0 ok, 1 error, CLI11's code
//! for usage errors, 0 for --help). Every error is one line on stderr.
inline int runTool(CLI::App& app, int argc, char** argv, const std::function<void()>& body) {
  installTempFileCleanup();
  std::string max_memory;
  app.add_option("--max-memory", max_memory,
                 "the most memory one input may take once decoded, from its header before anything is read (bytes, "
                 "or K, M, G; default: half this machine's memory, less under ulimit -v; also SHANSHUI_MAX_MEMORY)")
      ->option_text("SIZE");
  try {
    app.parse(argc, argv);
    if (!max_memory.empty()) {
      setMemoryBudget(parseByteSize(max_memory, "--max-memory"));
      ::setenv("SHANSHUI_MAX_MEMORY", max_memory.c_str(), 1);  // for the programs this one runs
    }
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    // A usage error is one line too, like every other error.
    std::fprintf(stderr, "%s: error: %s (see --help)\n", app.get_name().c_str(), e.what());
    return e.get_exit_code();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", app.get_name().c_str(), e.what());
    return 2;
  }
  try {
    body();
    return 0;
  } catch (const std::bad_alloc&) {
    const std::string last = lastInputFile();
    std::fprintf(stderr,
                 "%s: error: %s%sout of memory%s: the input or the requested size is too large (--max-memory)\n",
                 app.get_name().c_str(), last.c_str(), last.empty() ? "" : ": ", addressSpaceLimitNote().c_str());
    endIfMemoryRanOut();
    return 1;
  } catch (const std::system_error& e) {
    // A thread that cannot start (its stack is address space; OpenCV and the GL driver start
    // them) is memory running out as much as a failed allocation is.
    const bool memory =
        e.code() == std::errc::resource_unavailable_try_again || e.code() == std::errc::not_enough_memory;
    std::fprintf(stderr, "%s: error: %s%s%s\n", app.get_name().c_str(), memory ? "could not start a thread: " : "",
                 e.what(), memory ? addressSpaceLimitNote().c_str() : "");
    endIfMemoryRanOut();
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", app.get_name().c_str(), e.what());
    endIfMemoryRanOut();
    return 1;
  }
}

//! runTool for the asset tools, which also run in batches: `--manifest FILE` runs the
//! program once per line of FILE (see batch.h); --help describes it.
inline int runBatchableTool(CLI::App& app, int argc, char** argv, const std::function<void()>& body) {
  std::string manifest_help;
  app.add_option("--manifest", manifest_help,
                 "batch: run once per line of FILE ('-' reads stdin), each line the arguments of one item; the other "
                 "arguments given here apply to every item")
      ->option_text("FILE");
  app.footer(app.get_footer() +
             "\n\nBatch: --manifest FILE runs one item per line (the arguments after the program's name, shell "
             "quoting, # comments). Failed items are listed at the end and the rest still run; exit code 1 if any "
             "failed.\n  " +
             app.get_name() + " --manifest items.txt");
  if (const std::optional<int> code = runManifest(app, argc, argv)) return *code;
  return runTool(app, argc, argv, body);
}

}  // namespace shanshui::tools
