#version 450 core
// Feature lines (seed 001 Eq. 1; SPEC.md section 6): col = 1 − k·R_CurveFactor, a line
// where col < Curv0 (smoothstep of the soft width around it), plus silhouettes where N·V is
// small and where the depth jumps to something farther away (or to the background).
#include "ink_objects.glsl"

layout(binding = 0) uniform sampler2D u_normal_curvature;
layout(binding = 1) uniform sampler2D u_position_id;
uniform vec3 u_eye;

layout(location = 0) out vec2 o_line;  // line weight in [0, 1], col_i clamped to [0, 1]

float distanceAt(ivec2 p) {
  vec4 q = texelFetch(u_position_id, clamp(p, ivec2(0), textureSize(u_position_id, 0) - 1), 0);
  return objectId(q) == 0 ? 3.0e38 : distance(u_eye, q.xyz);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 position_id = texelFetch(u_position_id, p, 0);
  int id = objectId(position_id);
  if (id == 0) {
    o_line = vec2(0.0, 1.0);
    return;
  }
  ObjectParams o = objects[id - 1];
  int flags = int(o.line_misc.w);
  if ((flags & kLinesOn) == 0) {
    o_line = vec2(0.0, 1.0);
    return;
  }
  vec4 nc = texelFetch(u_normal_curvature, p, 0);
  float col = 1.0 - nc.w * o.line_color.w;
  float threshold = o.bg_color.w, soft = o.line_misc.x;
  float weight = 0.0;
  if ((flags & kNormalOnly) == 0) {
    weight = soft > 0.0 ? 1.0 - smoothstep(threshold - 0.5 * soft, threshold + 0.5 * soft, col)
                        : (col < threshold ? 1.0 : 0.0);
  }
  float silhouette = o.line_misc.y;
  if (silhouette > 0.0) {
    float n_dot_v = abs(dot(normalize(nc.xyz), normalize(u_eye - position_id.xyz)));
    weight = max(weight, 1.0 - smoothstep(0.5 * silhouette, silhouette, n_dot_v));
  }
  float jump = o.line_misc.z;
  if (jump > 0.0) {
    float d = distance(u_eye, position_id.xyz);
    float farthest = max(max(distanceAt(p + ivec2(1, 0)), distanceAt(p - ivec2(1, 0))),
                         max(distanceAt(p + ivec2(0, 1)), distanceAt(p - ivec2(0, 1))));
    if (farthest - d > jump * d) weight = 1.0;
  }
  o_line = vec2(weight, clamp(col, 0.0, 1.0));
}
