#version 450 core
// Interior shading (seed 001 Eqs. 2, 3, 5; SPEC.md section 7): diffuse term, eroded by
// noise or by the wrinkle texture where the line pass left background (Eq. 3 with β a
// parameter), times the line value col_i, plus noise, then five ink tones with
// Gaussian-smoothed steps.
#include "ink_objects.glsl"
#include "ink_gaussian_cdf.glsl"

layout(binding = 0) uniform sampler2D u_normal_curvature;
layout(binding = 1) uniform sampler2D u_position_id;
layout(binding = 2) uniform sampler2D u_surface;
#ifdef LINES
layout(binding = 3) uniform sampler2D u_lines;
#endif
uniform vec3 u_light_dir;  // unit, towards the light

layout(location = 0) out float o_tone;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  int id = objectId(texelFetch(u_position_id, p, 0));
  if (id == 0) {
    o_tone = 1.0;
    return;
  }
  ObjectParams o = objects[id - 1];
  int flags = int(o.shade_misc2.z);
  if ((flags & kShadingOn) == 0) {
    o_tone = 1.0;
    return;
  }
  vec3 n = normalize(texelFetch(u_normal_curvature, p, 0).xyz);
  float n_dot_l = dot(n, u_light_dir);
  float t_d = (flags & kHalfLambert) != 0 ? 0.5 * n_dot_l + 0.5 : max(n_dot_l, 0.0);
  vec4 surface = texelFetch(u_surface, p, 0);
  float line_weight = 0.0, col = 1.0;
#ifdef LINES
  vec2 line = texelFetch(u_lines, p, 0).rg;
  line_weight = line.x;
  col = line.y;
#endif
  // Eq. 3's erosion coefficient: from the noise texture, or (Eq. 5) from the wrinkle
  // texture, which is only mapped where the line pass gave background.
  float t_w = 1.0 - o.shade_misc.w * (1.0 - surface.r);
#ifdef WRINKLE
  if ((flags & kWrinkled) != 0 && line_weight < 0.5) t_w = surface.b * o.shade_misc2.y;
#endif
  float t = clamp(t_d + t_w + o.shade_misc.z, 0.0, 1.0);
  if ((flags & kLineValue) != 0) t *= col;
  t += o.shade_misc2.x * (2.0 * surface.g - 1.0);
  float sigma = o.shade_misc.y;
  float tone = o.tones.x;
  float c[5] = float[5](o.tones.x, o.tones.y, o.tones.z, o.tones.w, o.shade_misc.x);
  for (int k = 0; k < 4; ++k) {
    float s = sigma > 0.0 ? gaussianCdf((t - o.thresholds[k]) / sigma) : (t > o.thresholds[k] ? 1.0 : 0.0);
    tone += (c[k + 1] - c[k]) * s;
  }
  o_tone = tone;
}
