#version 450 core
// Ink diffusion, main region, step 1 of the separable city-block distance transform: along
// each row, the distance to the nearest stroke pixel and that pixel's ink (ties keep the
// larger ink), by a forward and a backward sweep. One invocation per row.
//
// Only distances up to d (u_ring_steps) can make a ring pixel, so only those are stored:
// the pass clears the images to "far" first (a fill costs far less than a store per
// pixel), and a larger distance left as "far" changes no ring — the smallest distance to a
// ring pixel is found through pixels that are themselves within d.
layout(local_size_x = 64) in;
layout(r32f, binding = 0) readonly uniform image2D u_ink;
layout(r32i, binding = 1) uniform iimage2D u_distance;
layout(r32f, binding = 2) uniform image2D u_source;
uniform float u_threshold;
uniform int u_ring_steps;

const int kFar = 1 << 28;

void main() {
  int y = int(gl_GlobalInvocationID.x);
  ivec2 size = imageSize(u_ink);
  if (y >= size.y) return;
  int d = kFar;
  float v = 0.0;
  for (int x = 0; x < size.x; ++x) {
    float ink = imageLoad(u_ink, ivec2(x, y)).r;
    if (ink > u_threshold) {
      d = 0;
      v = ink;
    } else if (d < kFar) {
      d += 1;
    }
    if (d <= u_ring_steps) {
      imageStore(u_distance, ivec2(x, y), ivec4(d));
      imageStore(u_source, ivec2(x, y), vec4(v));
    }
  }
  d = kFar;
  v = 0.0;
  for (int x = size.x - 1; x >= 0; --x) {
    if (d < kFar) d += 1;
    int dc = imageLoad(u_distance, ivec2(x, y)).r;
    if (dc < d || (dc == d && imageLoad(u_source, ivec2(x, y)).r >= v)) {
      d = dc;
      v = imageLoad(u_source, ivec2(x, y)).r;
    } else if (d <= u_ring_steps) {
      imageStore(u_distance, ivec2(x, y), ivec4(d));
      imageStore(u_source, ivec2(x, y), vec4(v));
    }
  }
}
