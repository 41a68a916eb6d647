#!/usr/bin/env bash
# The frame cost of trees and moss dots (issue 44), measured side by side: each sample with
# elements and the same scene without them, alternating, twice, at 1024², with
# `shanshui-render --benchmark` (frames back to back, GPU timestamps per pass). Run here
# (llvmpipe) or on a lent GPU from the device kit (R=.gpu/bin/shanshui-render).
# Usage: scripts/gpu_elements_bench.sh [OUT_DIR] [FRAMES]
set -euo pipefail
R=${R:-build/bin/shanshui-render}
out=${1:-out/elements_bench}
frames=${2:-300}
mkdir -p "$out"
for round in 1 2; do
  for scene in default grove; do
    "$R" "samples/scenes/$scene.json" --benchmark "$frames" --size 1024x1024 --stats "$out/${scene}_with_$round.json" \
      > "$out/${scene}_with_$round.txt"
    "$R" "samples/scenes/$scene.json" --benchmark "$frames" --size 1024x1024 --stats "$out/${scene}_without_$round.json" \
      --set objects.0.trees.enabled=false --set objects.0.dots.enabled=false > "$out/${scene}_without_$round.txt"
  done
done
tail -n +1 "$out"/*.txt
