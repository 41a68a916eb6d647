#version 450 core
// Ink diffusion, main region, step 1 of the separable city-block distance transform: along
// each row, the nearest stroke pixel (its distance and ink as one key, see
// ink_diffusion_nearest.glsl; ties keep the larger ink), by a forward and a backward
// sweep. One invocation per row.
//
// Only distances up to d (u_ring_steps) can make a ring pixel, so only those are stored:
// the pass clears the image to "far" first (a fill costs far less than a store per
// pixel), and a larger distance left as "far" changes no ring — the smallest distance to a
// ring pixel is found through pixels that are themselves within d. Blocks of BLOCK_SIZE
// pixels that no stroke lies within d of (u_near = 0) hold no such distance and are
// skipped: the stroke carried into them is farther than d, so it leaves them "far". An
// invocation's row and its 7 neighbours share a block row, so on llvmpipe the skip is
// taken by whole vectors.
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
#include "ink_diffusion_nearest.glsl"
layout(rg32f, binding = 0) readonly uniform image2D u_ink;  // two pixels to a texel (x in channel x & 1)
layout(r32ui, binding = 1) uniform uimage2D u_nearest;
uniform float u_threshold;
uniform int u_ring_steps;
layout(r8ui, binding = 3) readonly uniform uimage2D u_near;
uniform ivec2 u_lo, u_hi;  // the window computed (pixels, u_lo on whole blocks): its edge is the row's end

void main() {
  int y = u_lo.y + int(gl_GlobalInvocationID.x);
  const ivec2 size = u_hi;
  if (y >= size.y) return;
  const int first = u_lo.x / BLOCK_SIZE, blocks = (size.x + BLOCK_SIZE - 1) / BLOCK_SIZE, by = y / BLOCK_SIZE;
  uint key = kFar;
  for (int b = first; b < blocks; ++b) {
    if (imageLoad(u_near, ivec2(b, by)).r == 0u) {
      key = kFar;
      continue;
    }
    for (int x = b * BLOCK_SIZE; x < min((b + 1) * BLOCK_SIZE, size.x); ++x) {
      float ink = imageLoad(u_ink, ivec2(x >> 1, y))[x & 1];
      key = ink > u_threshold ? strokeKey(ink) : further(key, u_ring_steps);
      if (key != kFar) imageStore(u_nearest, ivec2(x, y), uvec4(key));
    }
  }
  key = kFar;
  for (int b = blocks - 1; b >= first; --b) {
    if (imageLoad(u_near, ivec2(b, by)).r == 0u) {
      key = kFar;
      continue;
    }
    for (int x = min((b + 1) * BLOCK_SIZE, size.x) - 1; x >= b * BLOCK_SIZE; --x) {
      key = further(key, u_ring_steps);
      uint stored = imageLoad(u_nearest, ivec2(x, y)).r;
      if (stored <= key) key = stored;
      else imageStore(u_nearest, ivec2(x, y), uvec4(key));
    }
  }
}
