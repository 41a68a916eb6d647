#!/usr/bin/env bash
# make fuzz: builds the libFuzzer targets of fuzz/ with clang (ASan + UBSan) in build-fuzz/
# and runs each for FUZZ_SECONDS (default 30; FUZZ_TARGETS picks some). New interesting inputs collect in
# build-fuzz/corpus/<name>/; a crash, leak or timeout is saved in build-fuzz/findings/ and
# fails the run. Copy a finding into fuzz/regressions/<name>/ once it is fixed, so the test
# suite replays it from then on.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
jobs=${JOBS:-$(nproc)}
# FUZZ_TARGETS="ply off" runs only those.
read -r -a targets <<< "${FUZZ_TARGETS:-obj ply off gltf glb fbx dae stl dem asc geotiff scene manifest png jpg tif pgm}"

CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DSHANSHUI_FUZZ=ON -DSHANSHUI_BUILD_TESTS=OFF -DSHANSHUI_BUILD_BENCH=OFF -DSHANSHUI_WERROR=OFF >/dev/null
cmake --build build-fuzz -j "$jobs" --target "${targets[@]/#/fuzz_}"

failed=()
for t in "${targets[@]}"; do
  mkdir -p "build-fuzz/corpus/$t" "build-fuzz/findings/$t"
  seeds=("fuzz/corpus/$t")
  [ -d "fuzz/regressions/$t" ] && seeds+=("fuzz/regressions/$t")
  echo "fuzz: $t for ${seconds} s" >&2
  if ! ASAN_OPTIONS=detect_leaks=0 "build-fuzz/bin/fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 \
      -max_len=65536 -artifact_prefix="build-fuzz/findings/$t/" -print_final_stats=1 \
      "build-fuzz/corpus/$t" "${seeds[@]}" > "build-fuzz/findings/$t.log" 2>&1; then
    failed+=("$t")
    echo "fuzz: $t FOUND A PROBLEM: see build-fuzz/findings/$t.log and build-fuzz/findings/$t/" >&2
  fi
  grep -E "^stat::number_of_executed_units|^stat::new_units_added" "build-fuzz/findings/$t.log" | sed "s/^/  /" >&2 || true
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: findings in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, nothing found" >&2
