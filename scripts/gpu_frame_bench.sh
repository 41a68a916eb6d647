#!/usr/bin/env bash
# The frame on a GPU against issue 47's targets, every figure from one run: the default
# sample at 1024² (with and without its trees and dots) and at 3840x2160, the light-colour
# sample, the default sample with the tuned diffusion (n = 5, d = 3), lines and shading
# alone, the painting beside the level-distance sample (issue 45's cost), and the strokes
# gathered instead of stamped (SHANSHUI_STROKES=gather). Each with
# `shanshui-render --benchmark` (frames back to back, the camera turning, two frames in
# flight, GPU timestamps per pass read late, two seconds of warm-up). Run here (llvmpipe,
# give a small FRAMES) or on a lent GPU from the device kit (R=.gpu/bin/shanshui-render).
# Usage: scripts/gpu_frame_bench.sh [OUT_DIR] [FRAMES]
set -euo pipefail
R=${R:-build/bin/shanshui-render}
out=${1:-out/frame_bench}
frames=${2:-300}
mkdir -p "$out"
run() { # name scene size [--set ...]
  local name=$1 scene=$2 size=$3
  shift 3
  "$R" "samples/scenes/$scene.json" --benchmark "$frames" --size "$size" --stats "$out/$name.json" "$@" \
    > "$out/$name.txt" 2>&1 || echo "$name failed: $?" >> "$out/$name.txt"
}
for round in 1 2; do
  run "default_1024_$round" default 1024x1024
  run "default_noelements_1024_$round" default 1024x1024 \
    --set objects.0.trees.enabled=false --set objects.0.dots.enabled=false
  run "default_diffusion_1024_$round" default 1024x1024 --set diffusion.ring_steps=3 --set diffusion.iterations=5
  run "light_colour_1024_$round" light_colour 1024x1024
  run "painting_1024_$round" painting 1024x1024
  run "level_distance_1024_$round" level_distance 1024x1024
done
run lines_shading_1024 default 1024x1024 --set canvas.type=none --set mist.density=0 \
  --set objects.0.trees.enabled=false --set objects.0.dots.enabled=false
run default_2160 default 3840x2160
run default_diffusion_2160 default 3840x2160 --set diffusion.ring_steps=3 --set diffusion.iterations=5
# The strokes gathered instead of stamped (SHANSHUI_STROKES=gather, off by default until
# timed here): the lines and ink passes at 1024² and 4K, beside the rows above.
for round in 1 2; do
  SHANSHUI_STROKES=gather run "default_gather_1024_$round" default 1024x1024
  SHANSHUI_STROKES=gather run "painting_gather_1024_$round" painting 1024x1024
done
SHANSHUI_STROKES=gather run default_gather_2160 default 3840x2160
tail -n +1 "$out"/*.txt
