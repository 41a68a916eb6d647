#version 450 core
// Ink diffusion, main region, step 2: the same two sweeps down each column over the row
// results give the exact city-block distance r to the stroke region; ring pixels
// (1 ≤ r ≤ d) take max(own ink, f^r · source ink). One invocation per pair of columns,
// which share a texel of u_main (the ink from the extraction, two pixels to a texel: x in
// channel x & 1), sweeping both side by side. As in the rows, only distances up to d are
// stored, and u_main is written only where a ring raises it. Blocks that no stroke lies within d of are skipped
// as in the rows (an invocation's column and its 7 neighbours share a block column).
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
layout(r32i, binding = 1) uniform iimage2D u_distance;
layout(r32f, binding = 2) uniform image2D u_source;
layout(rg32f, binding = 3) uniform image2D u_main;  // the ink, raised where a ring is darker
uniform int u_ring_steps;
layout(r8ui, binding = 4) readonly uniform uimage2D u_near;
uniform float u_ring_ink[RING_TABLE];  // f^r for r = 0 … d (pow per pixel costs more on llvmpipe)

const int kFar = 1 << 28;

// One step of a sweep: the carried stroke is one step further; the pixel's stored result
// wins if nearer (or as near with at least as much ink), else the carried one is stored
// where it is within d. Returns with (d, v) the pixel's result.
void step(ivec2 p, inout int d, inout float v, bool store) {
  if (d < kFar) d += 1;
  int dc = imageLoad(u_distance, p).r;
  if (dc < d || (dc == d && imageLoad(u_source, p).r >= v)) {
    d = dc;
    v = imageLoad(u_source, p).r;
  } else if (store && d <= u_ring_steps) {
    imageStore(u_distance, p, ivec4(d));
    imageStore(u_source, p, vec4(v));
  }
}

void main() {
  const int x = 2 * int(gl_GlobalInvocationID.x);  // the pair's first column
  ivec2 size = imageSize(u_distance);
  if (x >= size.x) return;
  const int columns = min(2, size.x - x);
  const int blocks = (size.y + BLOCK_SIZE - 1) / BLOCK_SIZE, bx = x / BLOCK_SIZE;  // one block column (BLOCK_SIZE is even)
  ivec2 d = ivec2(kFar);
  vec2 v = vec2(0.0);
  for (int b = 0; b < blocks; ++b) {
    if (imageLoad(u_near, ivec2(bx, b)).r == 0u) {
      d = ivec2(kFar);
      continue;
    }
    for (int y = b * BLOCK_SIZE; y < min((b + 1) * BLOCK_SIZE, size.y); ++y)
      for (int i = 0; i < columns; ++i) step(ivec2(x + i, y), d[i], v[i], true);
  }
  d = ivec2(kFar);
  v = vec2(0.0);
  for (int b = blocks - 1; b >= 0; --b) {
    if (imageLoad(u_near, ivec2(bx, b)).r == 0u) {
      d = ivec2(kFar);
      continue;
    }
    for (int y = min((b + 1) * BLOCK_SIZE, size.y) - 1; y >= b * BLOCK_SIZE; --y) {
      bool raised = false;
      vec2 ink = imageLoad(u_main, ivec2(x / 2, y)).rg;
      for (int i = 0; i < columns; ++i) {
        step(ivec2(x + i, y), d[i], v[i], false);
        if (d[i] >= 1 && d[i] <= u_ring_steps) {
          float ring = u_ring_ink[d[i]] * v[i];
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
