#version 450 core
// The motion blur pass (seed 004): paint dragged behind a moving object, over whatever lies
// behind it. A moving surface itself is drawn as it is; for any other pixel p:
// - the fastest moving surface within reach (the neighbour-maximum tile of p, from
//   motion_blur_tiles.frag) gives the motion to follow;
// - from p, a march along that surface's motion finds the nearest point of a surface
//   moving the same way within the trail, k × |v| long: its distance d and, just inside
//   it, the dragged colour C_n (Eq. 6's "colour of the nearest boundary");
// - Eq. 6, with x = d / (k|v|): C_blur = C_n + (C_under − C_n) · f, f = 2x(1 − a) for
//   a ≥ 0.5, 2xa + 1 − 2a below (C_under, the picture at p, stands for the paper);
// - Eq. 7 (water): W = 1 − 2x(1 − w) for w ≥ 0.5; below, W = 1 − x / (2w), which runs dry
//   at x = 2w (the printed 1 − 2dw / (k|v|) would keep more water for less, against the
//   text: "below 0.5 it runs out on the way");
// - Eq. 8: where 1 − W ≥ h (the paper's height) the paper shows; elsewhere the paint,
//   pulled towards C_n in the paper's valleys by the granulation g: mix(C_blur, C_n,
//   g W (1 − h)) (the printed C_blur − C_paper W (1 − h) would darken bare paper too);
// - §3.5: across the trail, bristle stripes carry more or less paint (a × (1 − bristles · r)).
#include "pixel_stage.glsl"
layout(binding = 0) uniform sampler2D u_picture;
layout(binding = 1) uniform sampler2D u_velocity;
layout(binding = 2) uniform sampler2D u_height;  // canvas grain (CANVAS) or value noise
uniform float u_length;   // k
uniform float u_paint;    // a
uniform float u_water;    // w
uniform float u_bristles;
uniform float u_bristle_px;
uniform float u_granulation;
layout(binding = 3) uniform sampler2D u_neighbour_max;  // per tile: fastest velocity within reach
uniform int u_tile;  // pixels per tile
#ifdef PIXEL_COMPUTE
layout(binding = 7, rgba8) writeonly uniform image2D o_colour_image;
vec4 o_colour;
void pixelOutputsClear() { o_colour = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(o_colour_image, p, o_colour); }
#else
out vec4 o_colour;
#endif

float hash(vec2 p) {
  return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453);
}

float heightAt(ivec2 p) {
  ivec2 n = textureSize(u_height, 0);
#ifdef CANVAS
  return clamp(0.5 + texelFetch(u_height, clamp(p, ivec2(0), n - 1), 0).r / 6.0, 0.0, 1.0);
#else
  return texelFetch(u_height, ((p % n) + n) % n, 0).r;
#endif
}

bool moving(vec4 v) {
  return v.a > 0.5 && dot(v.xy, v.xy) > 0.25;
}

void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
  ivec2 size = textureSize(u_picture, 0);
  vec4 picture = texelFetch(u_picture, p, 0);
  o_colour = picture;
  if (moving(texelFetch(u_velocity, p, 0))) return;

  float best = 1e30;
  vec2 best_v = vec2(0.0);
  vec3 c_n = vec3(0.0);
  vec4 vq = texelFetch(u_neighbour_max, p / u_tile, 0);
  if (vq.a < 0.5) return;
  float speed = length(vq.xy);
  vec2 dir = vq.xy / speed;
  float trail = u_length * speed;
  float step = max(1.0, trail / 48.0);
  for (float d = step; d <= trail + 0.5 * step; d += step) {
    ivec2 t = p + ivec2(round(dir * d));
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) break;
    vec4 vt = texelFetch(u_velocity, t, 0);
    if (moving(vt) && dot(vt.xy, dir) > 0.5 * speed) {
      best = d;
      best_v = vt.xy;
      vec3 sum = vec3(0.0);
      for (int k = 1; k <= 3; ++k)
        sum += texelFetch(u_picture, clamp(t + ivec2(round(dir * float(k))), ivec2(0), size - 1), 0).rgb;
      c_n = sum / 3.0;
      break;
    }
  }
  if (best > 1e29) return;

  float passing = length(best_v);
  float x = clamp(best / max(u_length * passing, 1e-3), 0.0, 1.0);
  vec2 across = vec2(-best_v.y, best_v.x) / passing;
  float bristle = hash(vec2(floor(dot(vec2(p), across) / u_bristle_px), 7.0));
  float a = u_paint * (1.0 - u_bristles * bristle);
  float f = a >= 0.5 ? 2.0 * x * (1.0 - a) : 2.0 * x * a + 1.0 - 2.0 * a;
  vec3 c_blur = mix(c_n, picture.rgb, clamp(f, 0.0, 1.0));
  float w = u_water;
  float water = clamp(w >= 0.5 ? 1.0 - 2.0 * x * (1.0 - w) : 1.0 - x / max(2.0 * w, 1e-3), 0.0, 1.0);
  float h = heightAt(p);
  if (1.0 - water >= h) return;
  o_colour = vec4(mix(c_blur, c_n, u_granulation * water * (1.0 - h)), picture.a);
}
#include "pixel_main.glsl"
