#version 450 core
// Composite: ink on paper. Interior colour = paper · BgColor · tone, lines blended in with
// their weight, then the distance fade moves far surfaces towards the paper.
#include "ink_objects.glsl"

layout(binding = 1) uniform sampler2D u_position_id;
#ifdef SHADING
layout(binding = 2) uniform sampler2D u_tone;
#endif
#ifdef LINES
layout(binding = 3) uniform sampler2D u_lines;
#endif
uniform vec3 u_eye;
uniform vec3 u_paper;
uniform float u_fade;       // strength, [0, 1]
uniform vec2 u_fade_range;  // distances where the fade starts and is full

layout(location = 0) out vec4 o_colour;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 position_id = texelFetch(u_position_id, p, 0);
  int id = objectId(position_id);
  if (id == 0) {
    o_colour = vec4(u_paper, 1.0);
    return;
  }
  ObjectParams o = objects[id - 1];
  float tone = 1.0;
#ifdef SHADING
  tone = texelFetch(u_tone, p, 0).r;
#endif
  vec3 colour = u_paper * o.bg_color.rgb * tone;
#ifdef LINES
  colour = mix(colour, o.line_color.rgb, texelFetch(u_lines, p, 0).r);
#endif
  float d = distance(u_eye, position_id.xyz);
  float fade = u_fade * smoothstep(u_fade_range.x, u_fade_range.y, d);
  o_colour = vec4(mix(colour, u_paper, fade), 1.0);
}
