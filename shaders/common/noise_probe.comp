#version 450 core
// Evaluates the GLSL noises at given points, for the tests that hold them to libs/noise.
#include "noise_perlin.glsl"
#include "noise_gabor.glsl"
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };  // xyz
layout(std430, binding = 1) writeonly buffer Values { float values[]; };
uniform int u_count;
uniform int u_kind;  // 0: perlin(xyz), 1: gaborNoise(xy)
uniform vec4 u_gabor;  // K, a, F0, omega0
uniform vec2 u_gabor_misc;  // isotropic (0 or 1), N′
uniform uint u_seed;

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= u_count) return;
  vec3 p = points[i].xyz;
  if (u_kind == 0) {
    values[i] = perlin(p);
  } else {
    GaborParams g = GaborParams(u_gabor.x, u_gabor.y, u_gabor.z, u_gabor.w, u_gabor_misc.x > 0.5, u_gabor_misc.y, u_seed);
    values[i] = gaborNoise(p.xy, g);
  }
}
