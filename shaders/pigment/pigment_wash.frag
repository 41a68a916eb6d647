#version 450 core
// The pigment pass (seeds 000 and 003): each object's wash of colour laid by Kubelka–Munk
// over the ink picture, which is its ground. The wash is thinned where the atmosphere
// thinned the ink (the picture's alpha, from the ink pass), optionally follows the ink
// (thicker where the picture is darker than the paper), and varies with the object-space
// erosion noise of the G-buffer (seed 003's texture layer, which stays on the surface).
#include "pixel_stage.glsl"
#include "pigment_km.glsl"

struct Wash {
  vec4 s_thickness;  // S, thickness (0: no wash)
  vec4 a_follow;     // a, follow_ink
  vec4 b_texture;    // b, texture
};
layout(std430, binding = 0) readonly buffer Washes {
  Wash washes[];
};
layout(binding = 0) uniform sampler2D u_picture;
layout(binding = 1) uniform sampler2D u_surface_id;  // erosion noise, ..., object id / 255
layout(binding = 2) uniform sampler2D u_depth;
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
#ifdef PIXEL_COMPUTE
layout(binding = 7, rgba8) writeonly uniform image2D o_colour_image;
vec4 o_colour;
void pixelOutputsClear() { o_colour = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(o_colour_image, p, o_colour); }
#else
out vec4 o_colour;
#endif

float luma(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
  vec4 picture = texelFetch(u_picture, p, 0);
  o_colour = picture;
  if (texelFetch(u_depth, p, 0).r >= 1.0) return;
  vec4 surface = texelFetch(u_surface_id, p, 0);
  int id = int(round(surface.a * 255.0)) - 1;
  if (id < 0 || id >= washes.length()) return;
  Wash w = washes[id];
  float thickness = w.s_thickness.w;
  if (thickness <= 0.0) return;
  float ink = clamp(1.0 - luma(picture.rgb) / max(luma(u_paper), 1e-3), 0.0, 1.0);
  thickness *= picture.a * mix(1.0, smoothstep(0.0, 0.5, ink), w.a_follow.w);
  thickness *= 1.0 + w.b_texture.w * (2.0 * surface.r - 1.0);
  o_colour = vec4(kmOnGround(w.s_thickness.xyz, w.a_follow.xyz, w.b_texture.xyz, max(thickness, 0.0), picture.rgb),
                  picture.a);
}
#include "pixel_main.glsl"
