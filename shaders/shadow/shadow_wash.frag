#version 450 core
// The shadow pass (seed 003): where the shadow map shows a surface hidden from the light,
// a wash of the shadow's pigment, laid by Kubelka–Munk over the picture. The edge is
// filtered over a disc of `u_softness` texels (hardware-compared bilinear taps), and the
// wash thins with the atmosphere as the ink did (the picture's alpha, from the ink pass).
#include "pixel_stage.glsl"
#include "pigment_km.glsl"

layout(binding = 0) uniform sampler2D u_picture;
layout(binding = 1) uniform sampler2D u_depth;
layout(binding = 2) uniform sampler2DShadow u_shadow_map;
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
uniform mat4 u_light_view_projection;
uniform float u_bias;      // light-space depth units
uniform float u_softness;  // texels
uniform vec4 u_s_thickness;
uniform vec3 u_a;
uniform vec3 u_b;
#ifdef PIXEL_COMPUTE
layout(binding = 7, rgba8) writeonly uniform image2D o_colour_image;
layout(binding = 6, r8) writeonly uniform image2D o_shade_image;
vec4 o_colour;
float o_shade;  // for the edges pass: 0 lit .. 1 in shadow
void pixelOutputsClear() { o_colour = vec4(0.0); o_shade = 0.0; }
void pixelStore(ivec2 p) { imageStore(o_colour_image, p, o_colour); imageStore(o_shade_image, p, vec4(o_shade, 0.0, 0.0, 0.0)); }
#else
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_shade;  // for the edges pass: 0 lit .. 1 in shadow
#endif

// 0 lit, 1 in shadow, at a world position.
float shadowAt(vec3 world) {
  vec4 l = u_light_view_projection * vec4(world, 1.0);
  vec3 q = l.xyz / l.w * 0.5 + 0.5;
  if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return 0.0;
  float reference = q.z - u_bias;
  vec2 texel = 1.0 / vec2(textureSize(u_shadow_map, 0));
  // Twelve taps on two rings and the centre, each a bilinear 2x2 comparison.
  float lit = texture(u_shadow_map, vec3(q.xy, reference));
  float weight = 1.0;
  if (u_softness > 0.0) {
    for (int i = 0; i < 12; ++i) {
      float angle = 6.2831853 * (float(i) + 0.5 * float(i / 6)) / 6.0;
      float radius = u_softness * (i < 6 ? 0.5 : 1.0);
      vec2 offset = radius * vec2(cos(angle), sin(angle)) * texel;
      lit += texture(u_shadow_map, vec3(q.xy + offset, reference));
      weight += 1.0;
    }
  }
  return 1.0 - lit / weight;
}

void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
  vec4 picture = texelFetch(u_picture, p, 0);
  o_colour = picture;
  o_shade = 0.0;
  float depth = texelFetch(u_depth, p, 0).r;
  if (depth >= 1.0) return;
  vec2 ndc = (vec2(p) + 0.5) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
  vec4 w = u_inverse_view_projection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  float shade = shadowAt(w.xyz / w.w);
  o_shade = shade;
  float thickness = u_s_thickness.w * shade * picture.a;
  if (thickness <= 0.0) return;
  o_colour = vec4(kmOnGround(u_s_thickness.xyz, u_a, u_b, thickness, picture.rgb), picture.a);
}
#include "pixel_main.glsl"
