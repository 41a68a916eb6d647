#version 450 core
// Ink diffusion, main region, step 2: the same two sweeps down each column over the row
// results give the exact city-block distance r to the stroke region and the ink of a
// nearest stroke pixel (one key, see ink_diffusion_nearest.glsl); ring pixels
// (1 ≤ r ≤ d) take max(own ink, f^r · stroke ink). One invocation per pair of columns,
// which share a texel of u_main (the ink from the extraction, two pixels to a texel: x in
// channel x & 1), sweeping both side by side. As in the rows, only distances up to d are
// stored, and u_main is written only where a ring raises it. Blocks that no stroke lies
// within d of are skipped as in the rows (an invocation's columns and their 14 neighbours
// share a block column).
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
#include "ink_diffusion_nearest.glsl"
layout(r32ui, binding = 1) uniform uimage2D u_nearest;
layout(rg32f, binding = 3) uniform image2D u_main;  // the ink, raised where a ring is darker
uniform int u_ring_steps;
layout(r8ui, binding = 4) readonly uniform uimage2D u_near;
uniform float u_ring_ink[RING_TABLE];  // f^r for r = 0 … d (pow per pixel costs more on llvmpipe)
uniform ivec2 u_lo, u_hi;  // the window computed (pixels, u_lo on whole blocks): its edge is the column's end

// One step of a sweep: the carried stroke is one pixel further; the pixel's stored one
// wins if its key is no larger, else the carried one is stored (when `store`). Returns
// with `key` the pixel's result.
void step(ivec2 p, inout uint key, bool store) {
  key = further(key, u_ring_steps);
  uint stored = imageLoad(u_nearest, p).r;
  if (stored <= key) key = stored;
  else if (store) imageStore(u_nearest, p, uvec4(key));
}

void main() {
  const int x = u_lo.x + 2 * int(gl_GlobalInvocationID.x);  // the pair's first column
  const ivec2 size = u_hi;
  if (x >= size.x) return;
  const int columns = min(2, size.x - x);
  const int first = u_lo.y / BLOCK_SIZE, blocks = (size.y + BLOCK_SIZE - 1) / BLOCK_SIZE,
            bx = x / BLOCK_SIZE;  // one block column (BLOCK_SIZE is even)
  uvec2 key = uvec2(kFar);
  for (int b = first; b < blocks; ++b) {
    if (imageLoad(u_near, ivec2(bx, b)).r == 0u) {
      key = uvec2(kFar);
      continue;
    }
    for (int y = b * BLOCK_SIZE; y < min((b + 1) * BLOCK_SIZE, size.y); ++y)
      for (int i = 0; i < columns; ++i) step(ivec2(x + i, y), key[i], true);
  }
  key = uvec2(kFar);
  for (int b = blocks - 1; b >= first; --b) {
    if (imageLoad(u_near, ivec2(bx, b)).r == 0u) {
      key = uvec2(kFar);
      continue;
    }
    for (int y = min((b + 1) * BLOCK_SIZE, size.y) - 1; y >= b * BLOCK_SIZE; --y) {
      bool raised = false;
      vec2 ink = imageLoad(u_main, ivec2(x / 2, y)).rg;
      for (int i = 0; i < columns; ++i) {
        step(ivec2(x + i, y), key[i], false);
        int r = int(keyDistance(key[i]));
        if (key[i] != kFar && r >= 1) {
          float ring = u_ring_ink[r] * keyInk(key[i]);
          if (ring > ink[i]) {
            ink[i] = ring;
            raised = true;
          }
        }
      }
      if (raised) imageStore(u_main, ivec2(x / 2, y), vec4(ink, 0.0, 0.0));
    }
  }
}
