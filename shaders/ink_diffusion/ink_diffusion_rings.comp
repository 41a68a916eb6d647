#version 450 core
// Ink diffusion, main region, as one gather (InkDiffusionPass's layout for a GPU, for d up
// to kMaxGatherSteps; the row and column sweeps are the layout for llvmpipe and large d):
// each invocation takes a texel of the extracted ink (a pair of columns, x in channel x & 1)
// and, for each of its two pixels, the smallest key (ink_diffusion_nearest.glsl: distance,
// then more ink) over the stroke pixels of the window within city-block distance d of it,
// which is the key the sweeps carry there; a ring pixel (1 ≤ r ≤ d) takes max(own ink,
// f^r · stroke ink). Every pixel of the window is written, into the other ping-pong image
// (the ink read here is the neighbours'). Thousands of invocations each reading the 2d² +
// 4d + 2 texels around it, where the sweeps give a row or a column to one invocation that
// walks it end to end.
layout(local_size_x = 8, local_size_y = 8) in;
#include "ink_diffusion_nearest.glsl"
layout(rg32f, binding = 0) readonly uniform image2D u_ink;     // after the extraction
layout(rg32f, binding = 2) writeonly uniform image2D u_raised;  // the ink with the rings
uniform float u_threshold;
uniform int u_ring_steps;
uniform float u_ring_ink[RING_TABLE];  // f^r for r = 0 … d
uniform ivec2 u_lo, u_hi;  // the window computed (pixels; u_lo.x even)

void main() {
  const ivec2 t = ivec2(u_lo.x / 2, u_lo.y) + ivec2(gl_GlobalInvocationID.xy);
  const int x0 = 2 * t.x, d = u_ring_steps;
  if (x0 >= u_hi.x || t.y >= u_hi.y) return;
  uvec2 key = uvec2(kFar);
  for (int dy = -d; dy <= d; ++dy) {
    const int y = t.y + dy;
    if (y < u_lo.y || y >= u_hi.y) continue;
    const int reach = d - abs(dy);  // columns within d of either pixel on this row
    const int first = max(x0 - reach, u_lo.x), last = min(x0 + 1 + reach, u_hi.x - 1);
    for (int x = first; x <= last; ++x) {
      const float ink = imageLoad(u_ink, ivec2(x >> 1, y))[x & 1];
      if (!(ink > u_threshold)) continue;
      const uint stroke = strokeKey(ink);
      for (int i = 0; i < 2; ++i) {
        const int r = abs(x - (x0 + i)) + abs(dy);
        if (r <= d) key[i] = min(key[i], stroke + (uint(r) << kInkBits));
      }
    }
  }
  vec2 own = imageLoad(u_ink, t).rg;
  for (int i = 0; i < 2; ++i) {
    // The unused half of the last texel of an odd width stays 0.
    if (key[i] == kFar || x0 + i >= u_hi.x) continue;
    const int r = int(keyDistance(key[i]));
    if (r >= 1) own[i] = max(own[i], u_ring_ink[r] * keyInk(key[i]));
  }
  imageStore(u_raised, t, vec4(own, 0.0, 0.0));
}
