#version 450 core
// Where motion blur looks for what passed over a pixel (McGuire et al. 2012's tile and
// neighbour maxima, in place of seed 004's random taps, which miss thin or distant objects
// and leave holes in the trail). NEIGHBOURS off: each texel is a u_tile × u_tile block of
// the velocity buffer, keeping its fastest moving surface's velocity (alpha 1 if any).
// NEIGHBOURS on: each tile keeps the fastest of the tiles within u_radius tiles.
#include "pixel_stage.glsl"
layout(binding = 0) uniform sampler2D u_source;
uniform int u_tile;    // pixels per tile (first stage)
uniform int u_radius;  // tiles (second stage)
#ifdef PIXEL_COMPUTE
layout(binding = 7, rgba16f) writeonly uniform image2D o_velocity_image;
vec4 o_velocity;
void pixelOutputsClear() { o_velocity = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(o_velocity_image, p, o_velocity); }
#else
out vec4 o_velocity;
#endif

void shadePixel() {
  ivec2 t = ivec2(PIXEL_COORD);
  ivec2 size = textureSize(u_source, 0);
  vec4 best = vec4(0.0);
#ifdef NEIGHBOURS
  for (int j = -u_radius; j <= u_radius; ++j)
    for (int i = -u_radius; i <= u_radius; ++i) {
      ivec2 q = t + ivec2(i, j);
      if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      vec4 v = texelFetch(u_source, q, 0);
      if (v.a > 0.5 && dot(v.xy, v.xy) > dot(best.xy, best.xy)) best = v;
    }
#else
  for (int j = 0; j < u_tile; ++j)
    for (int i = 0; i < u_tile; ++i) {
      ivec2 q = t * u_tile + ivec2(i, j);
      if (any(greaterThanEqual(q, size))) continue;
      vec4 v = texelFetch(u_source, q, 0);
      if (v.a > 0.5 && dot(v.xy, v.xy) > 0.25 && dot(v.xy, v.xy) > dot(best.xy, best.xy)) best = vec4(v.xy, 0.0, 1.0);
    }
#endif
  o_velocity = best;
}
#include "pixel_main.glsl"
