// The dissolving border (objects.N.border) and its noise, for every pass that needs what the
// border leaves of an object: the ink pass (ink_surface.glsl) and the elements' expand step,
// which keeps a tree off the paper where the ragged edge leaves none of its ground. Declare
// `u_value_noise` (an r8 image of borderNoiseTexture, render_pass.h) before including this.
#ifndef BORDER_NOISE_GLSL
#define BORDER_NOISE_GLSL

// Tiled fractal value noise in [0, 1] (libs/noise's erosion noise, 4 coarsest cells per
// tile), sampled finely enough (kValueNoiseTexels a side) that the nearest texel stands in
// for a filtered fetch: an image load costs llvmpipe about a quarter of a bilinear fetch,
// and the two fetches were a sixth of the lines pass (measured side by side).
const float kValueNoiseTexels = 1024.0;

// The noise at `uv` (one tile per unit). The texel 1.5 back along both axes is the one whose
// value a bilinear fetch of the 256² tile at uv would give on average.
float valueNoise(vec2 uv) {
  return imageLoad(u_value_noise, ivec2(floor(uv * kValueNoiseTexels - 1.5)) & int(kValueNoiseTexels - 1.0)).r;
}

// How deep model point m (x, y from its bounding box's centre; half_extent the box's half
// size) lies inside the box's edge, in falloff widths (width > 0).
float borderDepth(vec2 m, vec2 half_extent, float width) {
  vec2 inside = half_extent - abs(m);
  return min(inside.x, inside.y) / width;
}

// How much of an object the border leaves at model point m: 1 inside, 0 at the box's edge.
// The depth (borderDepth) pulled inwards by up to `roughness` widths of noise, so the edge
// is an irregular wash, never a straight cut, and always paper.
float borderLeft(vec2 m, vec2 half_extent, float width, float roughness) {
  float t = borderDepth(m, half_extent, width);
  if (t >= 1.0 + roughness) return 1.0;  // beyond the band the noise can reach: no noise
  // About one coarse noise cell per border width.
  float n = valueNoise(m / width * 0.25);
  return smoothstep(0.0, 1.0, t - roughness * n);
}

#endif
