// Batch use of a shanshui tool: `--manifest FILE` runs the tool once per line of FILE, each
// line holding that item's arguments as they would be typed after the program's name.
// Arguments given on the command line besides --manifest are added in front of every
// item's (shared options; an item may not repeat one). Each item runs as its own process
// (this same program), so one item's failure or crash cannot touch the others or their
// outputs; its output is echoed with an "[k/N]" prefix, and a summary names every failed
// item by manifest line with its error. Exit code 0 when all items succeed, 1 otherwise.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "subprocess.h"

namespace shanshui::tools {

struct ManifestItem {
  int line = 0;                   //!< 1-based line in the manifest
  std::vector<std::string> args;  //!< the item's words
  std::string error;              //!< a syntax error on the line (then args is empty)
};

//! Splits a manifest line into words the way a POSIX shell would for plain words: blanks
//! separate, '…' quotes literally, "…" quotes with \" and \\ escapes, a backslash outside
//! quotes escapes the next character, and an unquoted # starts a comment. Sets `error` for
//! an unterminated quote or a trailing backslash.
inline std::vector<std::string> splitManifestLine(const std::string& line, std::string* error) {
  std::vector<std::string> words;
  std::string word;
  bool in_word = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == ' ' || c == '\t') {
      if (in_word) words.push_back(word);
      word.clear();
      in_word = false;
    } else if (c == '#' && !in_word) {
      break;
    } else if (c == '\'') {
      const std::size_t end = line.find('\'', i + 1);
      if (end == std::string::npos) {
        *error = "unterminated ' quote";
        return {};
      }
      word += line.substr(i + 1, end - i - 1);
      in_word = true;
      i = end;
    } else if (c == '"') {
      std::size_t j = i + 1;
      for (; j < line.size() && line[j] != '"'; ++j) {
        if (line[j] == '\\' && j + 1 < line.size() && (line[j + 1] == '"' || line[j + 1] == '\\')) ++j;
        word += line[j];
      }
      if (j >= line.size()) {
        *error = "unterminated \" quote";
        return {};
      }
      in_word = true;
      i = j;
    } else if (c == '\\') {
      if (i + 1 >= line.size()) {
        *error = "trailing backslash";
        return {};
      }
      word += line[++i];
      in_word = true;
    } else {
      word += c;
      in_word = true;
    }
  }
  if (in_word) words.push_back(word);
  return words;
}

//! The items of a manifest ('-' reads stdin); blank and comment-only lines are skipped.
inline std::vector<ManifestItem> readManifest(const std::string& path) {
  // Through the input gate: a FIFO, a device or a directory is refused, and standard input
  // is bounded while it is read.
  const std::string text = path == "-" ? readInputStream(stdin, "stdin", "a --manifest", kMaxTextInputBytes)
                                       : readInputFile(path, "a --manifest (a text file)", kMaxTextInputBytes);
  std::istringstream in(text);
  std::vector<ManifestItem> items;
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    ManifestItem item;
    item.line = n;
    item.args = splitManifestLine(line, &item.error);
    if (item.args.empty() && item.error.empty()) continue;
    for (const std::string& a : item.args)
      if (a == "--manifest" || a.rfind("--manifest=", 0) == 0) item.error = "an item cannot name another manifest";
    if (!item.error.empty()) item.args.clear();
    items.push_back(std::move(item));
  }
  if (items.empty()) throw makeError(path == "-" ? "stdin" : path, ": the manifest has no items");
  return items;
}

//! With --manifest in argv (and no --help), runs the batch and returns the exit code;
//! otherwise returns nothing and the caller parses argv as usual.
inline std::optional<int> runManifest(const CLI::App& app, int argc, char** argv) {
  std::string manifest;
  std::vector<std::string> shared;
  int given = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") return std::nullopt;
    if (a == "--manifest" && i + 1 < argc) {
      manifest = argv[++i];
      ++given;
    } else if (a.rfind("--manifest=", 0) == 0) {
      manifest = a.substr(11);
      ++given;
    } else {
      shared.push_back(a);
    }
  }
  if (given == 0) return std::nullopt;
  const std::string name = app.get_name();
  try {
    if (given > 1) throw makeError("--manifest given ", given, " times; expected one manifest per call");
    const std::vector<ManifestItem> items = readManifest(manifest);
    const std::filesystem::path self = std::filesystem::canonical("/proc/self/exe");
    const std::filesystem::path log =
        std::filesystem::temp_directory_path() / (name + "-batch-" + std::to_string(::getpid()) + ".log");
    struct RemoveLog {
      std::filesystem::path path;
      ~RemoveLog() {
        std::error_code ec;
        std::filesystem::remove(path, ec);
      }
    } removeLog{log};
    std::vector<std::string> failures;
    const int n = static_cast<int>(items.size());
    for (int k = 0; k < n; ++k) {
      const ManifestItem& item = items[static_cast<std::size_t>(k)];
      const std::string prefix = "[" + std::to_string(k + 1) + "/" + std::to_string(n) + "] ";
      std::string error = item.error;
      if (error.empty()) {
        std::vector<std::string> args = shared;
        args.insert(args.end(), item.args.begin(), item.args.end());
        try {
          const ProgramRun run = runProgram(self, args, log, prefix);
          if (!run.ok) {
            error = run.last_line.empty() ? "failed with no message" : run.last_line;
            if (WIFSIGNALED(run.status)) error += " (killed by signal " + std::to_string(WTERMSIG(run.status)) + ")";
          }
        } catch (const Error& e) {
          error = e.what();
          std::fprintf(stderr, "%s%s: error: manifest line %d: %s\n", prefix.c_str(), name.c_str(), item.line,
                       error.c_str());
        }
      } else {
        std::fprintf(stderr, "%s%s: error: manifest line %d: %s\n", prefix.c_str(), name.c_str(), item.line,
                     error.c_str());
      }
      if (!error.empty()) failures.push_back("line " + std::to_string(item.line) + ": " + error);
    }
    std::fprintf(stderr, "%s: batch of %d: %d done, %zu failed\n", name.c_str(), n,
                 n - static_cast<int>(failures.size()), failures.size());
    for (const std::string& f : failures) std::fprintf(stderr, "  %s\n", f.c_str());
    return failures.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
    return 1;
  }
}

}  // namespace shanshui::tools
