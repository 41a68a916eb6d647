#!/usr/bin/env bash
# Fails when a C++ source of the repository differs from clang-format's layout
# (.clang-format); `make format` rewrites them. Run by CTest as style.clang_format.
set -euo pipefail
cd "$(dirname "$0")/.."
format=${CLANG_FORMAT:-$(command -v clang-format-14 || command -v clang-format)}
git ls-files -z 'apps/*.cpp' 'apps/*.h' 'libs/*.cpp' 'libs/*.h' 'tools/*.cpp' 'tools/*.h' 'tests/*.cpp' \
  'tests/*.h' 'bench/*.cpp' 'bench/*.h' 'fuzz/*.cpp' 'fuzz/*.h' | xargs -0 "$format" --dry-run --Werror
