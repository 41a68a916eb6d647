#version 450 core
// The static canvas (the "shower door" baseline): the same kernels as the dynamic canvas
// but fixed to the screen, scattered over cells of the kernel's radius (as gaborNoise does)
// and evaluated at the pixel centre. CANVAS_TILE draws the tile of the `tiles` canvas
// instead: u_cells × u_cells cells whose kernels repeat with that period, so the texture
// wraps without a seam.
#include "noise_gabor.glsl"
#ifndef CANVAS_SILK
#include "noise_perlin.glsl"
#endif
#include "canvas_kernel.glsl"

uniform float u_density;  // λ, kernels per square pixel
uniform uint u_seed;
#ifdef CANVAS_TILE
uniform int u_cells;
#endif
layout(location = 0) out vec2 o_canvas;  // grain; no marks

void main() {
  vec2 p = gl_FragCoord.xy;
  float r = u_kernel.x;
  float mean = u_density * r * r;
  vec2 c = floor(p / r);
  float sum = 0.0;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      ivec2 cell = ivec2(c) + ivec2(di, dj);
#ifdef CANVAS_TILE
      uint s = noiseCellSeed(((cell % u_cells) + u_cells) % u_cells, u_seed);
#else
      uint s = noiseCellSeed(cell, u_seed);
#endif
      int count = impulseCount(mean, noiseUnit(noiseStream(s, 0u)));
      for (int n = 0; n < count; ++n) {
        uint k = 1u + uint(n) * 6u;
        vec2 centre = (vec2(cell) + vec2(noiseUnit(noiseStream(s, k)), noiseUnit(noiseStream(s, k + 1u)))) * r;
        float w = 2.0 * noiseUnit(noiseStream(s, k + 2u)) - 1.0;
        vec3 e = vec3(noiseUnit(noiseStream(s, k + 3u)), noiseUnit(noiseStream(s, k + 4u)), noiseUnit(noiseStream(s, k + 5u)));
        sum += w * canvasKernel(p - centre, e);
      }
    }
  }
  o_canvas = vec2(sum * u_kernel_misc.w, 0.0);
}
