#version 450 core
// The edges pass (seed 003 §4.2): pigment pools at the edges of a wash. A blur of
// `u_samples`² taps over a square of `u_radius` pixels, each tap moved by noise, averages
// "same object as here", the depth and (SHADOW) the shadow around each pixel; where those
// averages differ from the pixel's own, a wash ends nearby (edge: the largest of twice the
// share of other objects, the relative depth change from 3 % to 15 %, and 1.5 × the shadow
// change), and its pigment is made denser: T^(1 + strength · edge) on the transmittance
// T = colour / paper (bare paper stays bare).
// The same noise moves where the picture is read by up to `u_wobble` pixels, so edges wobble
// as a hand-laid wash does.
#include "pixel_stage.glsl"
layout(binding = 0) uniform sampler2D u_picture;
layout(binding = 1) uniform sampler2D u_surface_id;
layout(binding = 2) uniform sampler2D u_depth;
layout(binding = 3) uniform sampler2D u_noise;  // value noise, RG in [0, 1], tiled
#ifdef SHADOW
layout(binding = 4) uniform sampler2D u_shadow;  // 0 lit .. 1 in shadow
#endif
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
uniform float u_strength;
uniform float u_radius;  // pixels
uniform int u_samples;   // per side
uniform float u_wobble;  // pixels
uniform float u_wobble_scale;  // pixels per noise texel
#ifdef PIXEL_COMPUTE
layout(binding = 7, rgba8) writeonly uniform image2D o_colour_image;
vec4 o_colour;
void pixelOutputsClear() { o_colour = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(o_colour_image, p, o_colour); }
#else
out vec4 o_colour;
#endif

float linearDepth(float d) {
  float z = d * 2.0 - 1.0;
  return 2.0 * u_near_far.x * u_near_far.y / (u_near_far.y + u_near_far.x - z * (u_near_far.y - u_near_far.x));
}

vec2 noiseAt(vec2 p) {  // smooth, in [-0.5, 0.5]
  return texture(u_noise, p / (u_wobble_scale * vec2(textureSize(u_noise, 0)))).rg - 0.5;
}

vec2 jitterAt(ivec2 p) {  // per tap, in [-0.5, 0.5]
  ivec2 n = textureSize(u_noise, 0);
  return texelFetch(u_noise, ((p * 7) % n + n) % n, 0).gr - 0.5;
}

int idAt(ivec2 p) {
  if (texelFetch(u_depth, p, 0).r >= 1.0) return -1;
  return int(round(texelFetch(u_surface_id, p, 0).a * 255.0));
}

void shadePixel() {
  ivec2 size = textureSize(u_picture, 0);
  ivec2 p = ivec2(PIXEL_COORD);
  vec2 at = vec2(p) + 0.5 + u_wobble * 2.0 * noiseAt(vec2(p));
  ivec2 q = clamp(ivec2(at), ivec2(0), size - 1);
  vec4 picture = texelFetch(u_picture, q, 0);
  int id = idAt(q);
  float depth = id < 0 ? 0.0 : linearDepth(texelFetch(u_depth, q, 0).r);
#ifdef SHADOW
  float shade = texelFetch(u_shadow, q, 0).r;
  float shade_sum = 0.0;
#endif
  float same = 0.0, depth_sum = 0.0;
  int n = max(u_samples, 1);
  float spacing = n > 1 ? 2.0 * u_radius / float(n - 1) : 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      vec2 offset = (vec2(i, j) - 0.5 * float(n - 1)) * spacing;
      ivec2 t = clamp(q + ivec2(round(offset + spacing * jitterAt(q + ivec2(i, j) * 13))), ivec2(0), size - 1);
      int tid = idAt(t);
      same += tid == id ? 1.0 : 0.0;
      if (id >= 0 && tid == id) depth_sum += linearDepth(texelFetch(u_depth, t, 0).r);
#ifdef SHADOW
      shade_sum += texelFetch(u_shadow, t, 0).r;
#endif
    }
  }
  float taps = float(n * n);
  float edge = 2.0 * (1.0 - same / taps);
  if (id >= 0 && same > 0.0)
    edge = max(edge, smoothstep(0.03, 0.15, abs(depth_sum / same - depth) / max(depth, 1e-6)));
#ifdef SHADOW
  edge = max(edge, 1.5 * abs(shade_sum / taps - shade));
#endif
  edge = clamp(edge, 0.0, 1.0);
  // Denser pigment on the transmittance up to the paper; paper grain brighter than the
  // nominal paper keeps its excess.
  vec3 t = picture.rgb / max(u_paper, vec3(1e-3));
  vec3 under = clamp(t, 0.0, 1.0);
  o_colour = vec4((pow(under, vec3(1.0 + u_strength * edge)) + (t - under)) * u_paper, picture.a);
}
#include "pixel_main.glsl"
