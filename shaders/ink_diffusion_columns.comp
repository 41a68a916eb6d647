#version 450 core
// Ink diffusion, main region, step 2: the same two sweeps down each column over the row
// results give the exact city-block distance r to the stroke region; ring pixels
// (1 ≤ r ≤ d) take max(own ink, f^r · source ink). One invocation per column. As in the
// rows, only distances up to d are stored, and u_main (the ink, from the extraction) is
// written only where a ring raises it. Blocks that no stroke lies within d of are skipped
// as in the rows (an invocation's column and its 7 neighbours share a block column).
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
layout(r32i, binding = 1) uniform iimage2D u_distance;
layout(r32f, binding = 2) uniform image2D u_source;
layout(r32f, binding = 3) uniform image2D u_main;  // the ink, raised where a ring is darker
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
  int x = int(gl_GlobalInvocationID.x);
  ivec2 size = imageSize(u_main);
  if (x >= size.x) return;
  const int blocks = (size.y + BLOCK_SIZE - 1) / BLOCK_SIZE, bx = x / BLOCK_SIZE;
  int d = kFar;
  float v = 0.0;
  for (int b = 0; b < blocks; ++b) {
    if (imageLoad(u_near, ivec2(bx, b)).r == 0u) {
      d = kFar;
      continue;
    }
    for (int y = b * BLOCK_SIZE; y < min((b + 1) * BLOCK_SIZE, size.y); ++y) step(ivec2(x, y), d, v, true);
  }
  d = kFar;
  v = 0.0;
  for (int b = blocks - 1; b >= 0; --b) {
    if (imageLoad(u_near, ivec2(bx, b)).r == 0u) {
      d = kFar;
      continue;
    }
    for (int y = min((b + 1) * BLOCK_SIZE, size.y) - 1; y >= b * BLOCK_SIZE; --y) {
      step(ivec2(x, y), d, v, false);
      if (d >= 1 && d <= u_ring_steps) {
        float ring = u_ring_ink[d] * v;
        if (ring > imageLoad(u_main, ivec2(x, y)).r) imageStore(u_main, ivec2(x, y), vec4(ring));
      }
    }
  }
}
