#version 450 core
// The substrate pass (seed 000 §4): the paper's relief acts on the dried paint.
// Height H in [0, 1] from the canvas's grain (CANVAS; unit variance, so H = 0.5 + g / 6) or
// from a tile of value noise, deepened or flattened about 0.5 by the roughness r (Eq. 1).
// Per pixel, on the pigment's transmittance T = colour / paper (paper is T = 1):
// - distortion: the picture is read a little downhill along the paper's normal;
// - dry brush (Eq. 2, first case): light ink reaches only the paper's peaks, so where the
//   application a = dry_brush · weight · (1 − ink) rises above H the valley is left bare,
//   over a soft edge of `dry_edge` in height;
// - granulation (Eqs. 3, 4, second case): pigment settles in the valleys, T^(1 + d · Hiv · D)
//   with Hiv = 1 − (0.2 H + 0.8) less its mean 0.1 (the seed's Hiv ≥ 0 darkens the whole
//   wash; centred, valleys gain what peaks lose and the shading's tone stays) and
//   d = d_a (1 − L) + 5 d_a L, d_a = 1.2 × weight (the seed's |1 − ε| + d_min with ε = 0 and
//   d_min = 0.2), L the wash's lightness (light washes granulate more);
// - lighting (Eq. 5): the scene's light, seen from the camera, rakes the relief:
//   1 − (1 − L·N) d_s, divided by its value on flat paper so the sheet keeps its brightness.
#include "pixel_stage.glsl"
layout(binding = 0) uniform sampler2D u_picture;  // bilinear, for the distortion
layout(binding = 1) uniform sampler2D u_height;   // canvas grain (R) or value noise (R)
layout(binding = 2) uniform sampler2D u_surface_id;
layout(binding = 3) uniform sampler2D u_depth;
layout(std430, binding = 0) readonly buffer Weights {
  vec4 weights[];  // per object: dry brush, granulation, lighting, distortion
};
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
uniform vec3 u_light;  // towards the light, view space (z towards the viewer)
uniform float u_roughness;
uniform float u_dry_brush;
uniform float u_dry_edge;
uniform float u_granulation;
uniform float u_lighting;
uniform float u_distortion;  // pixels
#ifdef PIXEL_COMPUTE
layout(binding = 7, rgba8) writeonly uniform image2D o_colour_image;
vec4 o_colour;
void pixelOutputsClear() { o_colour = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(o_colour_image, p, o_colour); }
#else
out vec4 o_colour;
#endif

float heightAt(ivec2 p) {
  ivec2 n = textureSize(u_height, 0);
#ifdef CANVAS
  float h = clamp(0.5 + texelFetch(u_height, clamp(p, ivec2(0), n - 1), 0).r / 6.0, 0.0, 1.0);
#else
  float h = texelFetch(u_height, ((p % n) + n) % n, 0).r;
#endif
  return clamp((h - 0.5) * u_roughness + 0.5, 0.0, 1.0);
}

float luma(vec3 c) {
  return dot(c, vec3(0.2126, 0.7152, 0.0722));
}

void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
  float h = heightAt(p);
  vec2 slope = 0.5 * vec2(heightAt(p + ivec2(1, 0)) - heightAt(p - ivec2(1, 0)),
                          heightAt(p + ivec2(0, 1)) - heightAt(p - ivec2(0, 1)));
  vec3 n = normalize(vec3(-8.0 * slope, 1.0));
  // The object here takes its share of each effect; the bare paper takes all of it.
  vec4 w = vec4(1.0);
  if (texelFetch(u_depth, p, 0).r < 1.0) {
    int id = int(round(texelFetch(u_surface_id, p, 0).a * 255.0)) - 1;
    if (id >= 0 && id < weights.length()) w = weights[id];
  }
  vec2 size = vec2(textureSize(u_picture, 0));
  vec4 picture = texture(u_picture, (vec2(p) + 0.5 + u_distortion * w.w * n.xy) / size);
  // The transmittance up to the paper; grain brighter than the nominal paper keeps its excess.
  vec3 ratio = picture.rgb / max(u_paper, vec3(1e-3));
  vec3 t = clamp(ratio, 0.0, 1.0);
  vec3 excess = ratio - t;
  float ink = 1.0 - luma(t);
  float a = u_dry_brush * w.x * (1.0 - ink);
  t = mix(t, vec3(1.0), smoothstep(0.0, u_dry_edge, a - h));
  float lightness = luma(t);
  float d = 1.2 * w.y;
  d = d * (1.0 - lightness) + 5.0 * d * lightness;
  // Hiv = 1 − (0.2 H + 0.8), less its mean over the paper (0.1), so the wash keeps its tone.
  t = pow(t, vec3(max(1.0 + d * (0.1 - 0.2 * h) * u_granulation, 0.0)));
  float d_s = u_lighting * w.z;
  float flat_lit = 1.0 - (1.0 - max(u_light.z, 0.0)) * d_s;
  float lit = (1.0 - (1.0 - max(dot(u_light, n), 0.0)) * d_s) / max(flat_lit, 1e-3);
  o_colour = vec4(clamp((t + excess) * u_paper * lit, 0.0, 1.0), picture.a);
}
#include "pixel_main.glsl"
