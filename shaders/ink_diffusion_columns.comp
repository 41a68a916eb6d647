#version 450 core
// Ink diffusion, main region, step 2: the same two sweeps down each column over the row
// results give the exact city-block distance r to the stroke region; ring pixels
// (1 ≤ r ≤ d) take max(own ink, f^r · source ink). One invocation per column.
layout(local_size_x = 64) in;
layout(r32f, binding = 0) readonly uniform image2D u_ink;
layout(r32i, binding = 1) uniform iimage2D u_distance;
layout(r32f, binding = 2) uniform image2D u_source;
layout(r32f, binding = 3) writeonly uniform image2D u_main;
uniform int u_ring_steps;
uniform float u_attenuation;

const int kFar = 1 << 28;

void main() {
  int x = int(gl_GlobalInvocationID.x);
  ivec2 size = imageSize(u_ink);
  if (x >= size.x) return;
  int d = kFar;
  float v = 0.0;
  for (int y = 0; y < size.y; ++y) {
    int dc = imageLoad(u_distance, ivec2(x, y)).r;
    float vc = imageLoad(u_source, ivec2(x, y)).r;
    if (d < kFar) d += 1;
    if (dc < d || (dc == d && vc >= v)) {
      d = dc;
      v = vc;
    } else {
      imageStore(u_distance, ivec2(x, y), ivec4(d));
      imageStore(u_source, ivec2(x, y), vec4(v));
    }
  }
  d = kFar;
  v = 0.0;
  for (int y = size.y - 1; y >= 0; --y) {
    int dc = imageLoad(u_distance, ivec2(x, y)).r;
    float vc = imageLoad(u_source, ivec2(x, y)).r;
    if (d < kFar) d += 1;
    if (dc < d || (dc == d && vc >= v)) {
      d = dc;
      v = vc;
    }
    float ink = imageLoad(u_ink, ivec2(x, y)).r;
    if (d >= 1 && d <= u_ring_steps) ink = max(ink, pow(u_attenuation, float(d)) * v);
    imageStore(u_main, ivec2(x, y), vec4(ink));
  }
}
