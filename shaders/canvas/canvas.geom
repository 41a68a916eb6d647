#version 450 core
// Dynamic canvas: each visible triangle of projected area A gets N = λA kernels at points
// drawn uniformly over it (barycentric (1 − √t, (1 − s)√t, s√t), seed 001 Eqs. 15-17) from a
// stream seeded by its model-space vertices, so a triangle keeps its kernels from frame to
// frame. Each kernel is a screen-aligned quad of half side r pixels: the paper moves with
// the surface but its grain keeps its size on screen. ⌊N⌋ kernels have full weight and one
// more has weight √frac(N), so the expected energy is exactly λA at every N and nothing
// jumps when N crosses an integer (Eq. 12's power-of-two rounding makes the contrast jump by
// up to 29 %). A triangle needing more than INVOCATIONS × QUADS kernels (the geometry
// shader's output limit) gets that many with weights raised by √(N / cap): the contrast
// stays, the grain gets coarser. A kernel is drawn when its centre is not hidden in the
// G-buffer (the background dome: where the G-buffer is empty).
#include "noise_gabor.glsl"
layout(triangles, invocations = INVOCATIONS) in;
layout(triangle_strip, max_vertices = 4 * QUADS) out;

in vec3 v_model[];
out vec2 g_offset;          // pixels from the kernel's centre
flat out vec4 g_impulse;    // weight, randoms e0 e1 e2

layout(binding = 0) uniform sampler2D u_depth;  // the G-buffer's
uniform vec2 u_viewport;    // pixels
uniform float u_radius;     // r, pixels
uniform float u_density;    // λ, kernels per square pixel
uniform uint u_seed;
uniform bool u_background;

uint vertexHash(vec3 p) {
  uvec3 b = floatBitsToUint(p);
  return noiseHash(b.x ^ noiseHash(b.y ^ noiseHash(b.z)));
}

void main() {
  vec4 c[3] = vec4[3](gl_in[0].gl_Position, gl_in[1].gl_Position, gl_in[2].gl_Position);
  if (c[0].w <= 0.0 || c[1].w <= 0.0 || c[2].w <= 0.0) return;  // crosses the eye plane
  vec3 s[3];
  for (int i = 0; i < 3; ++i) s[i] = vec3((c[i].xy / c[i].w * 0.5 + 0.5) * u_viewport, c[i].z / c[i].w * 0.5 + 0.5);
  // Off screen by more than a kernel: nothing of it can show.
  vec2 lo = min(min(s[0].xy, s[1].xy), s[2].xy), hi = max(max(s[0].xy, s[1].xy), s[2].xy);
  if (any(greaterThan(lo, u_viewport + u_radius)) || any(lessThan(hi, vec2(-u_radius)))) return;
  vec2 e1 = s[1].xy - s[0].xy, e2 = s[2].xy - s[0].xy;
  float cross_z = e1.x * e2.y - e1.y * e2.x;
  float n = u_density * 0.5 * abs(cross_z);
  if (n <= 0.0) return;
  // Depth tolerance: the triangle's own depth change over 1.5 pixels, so a kernel on a
  // steep face is not rejected by its neighbour's pixel.
  vec2 dz = abs(cross_z) > 1e-12 ? vec2((s[1].z - s[0].z) * e2.y - (s[2].z - s[0].z) * e1.y,
                                        (s[2].z - s[0].z) * e1.x - (s[1].z - s[0].z) * e2.x) / cross_z
                                 : vec2(0.0);
  float tolerance = 1.5 * (abs(dz.x) + abs(dz.y)) + 1e-5;

  const int cap = INVOCATIONS * QUADS;
  int count = min(int(ceil(n)), cap);
  float capped_weight = n > float(cap) ? sqrt(n / float(cap)) : 1.0;
  uint seed = noiseHash(vertexHash(v_model[0]) + vertexHash(v_model[1]) + vertexHash(v_model[2]) + u_seed);
  int first = gl_InvocationID * QUADS;
  int last = min(count, first + QUADS);
  vec2 half_ndc = 2.0 * u_radius / u_viewport;
  for (int q = first; q < last; ++q) {
    uint k = uint(q) * 6u;
    float su = noiseUnit(noiseStream(seed, k)), t = sqrt(noiseUnit(noiseStream(seed, k + 1u)));
    vec4 centre = (1.0 - t) * c[0] + (1.0 - su) * t * c[1] + su * t * c[2];
    vec3 ndc = centre.xyz / centre.w;
    ivec2 pixel = clamp(ivec2((ndc.xy * 0.5 + 0.5) * u_viewport), ivec2(0), ivec2(u_viewport) - 1);
    float scene_depth = texelFetch(u_depth, pixel, 0).r;
    bool visible = u_background ? scene_depth >= 1.0 : ndc.z * 0.5 + 0.5 <= scene_depth + tolerance;
    if (!visible) continue;
    float w = 2.0 * noiseUnit(noiseStream(seed, k + 2u)) - 1.0;
    float weight = float(q) + 1.0 <= n ? capped_weight : sqrt(n - float(q));
    vec4 impulse = vec4(w * weight, noiseUnit(noiseStream(seed, k + 3u)), noiseUnit(noiseStream(seed, k + 4u)),
                        noiseUnit(noiseStream(seed, k + 5u)));
    for (int corner = 0; corner < 4; ++corner) {
      vec2 offset = vec2(corner & 1, corner >> 1) * 2.0 - 1.0;
      gl_Position = vec4(centre.xy + offset * half_ndc * centre.w, centre.z, centre.w);
      g_offset = offset * u_radius;
      g_impulse = impulse;
      EmitVertex();
    }
    EndPrimitive();
  }
}
