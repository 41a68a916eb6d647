#version 450 core
// The elements' marks (libs/render/src/elements_pass.cpp): six vertices a mark, read from
// the storage buffer by gl_VertexID, each mark a quad around its segment a → b (round caps
// and a pixel of room for the edge's smoothing) on an upright billboard through the
// element's foot that faces the camera.
struct Mark {
  vec4 anchor_ink;  // the element's foot (world), ink
  vec4 ab;          // ends in the billboard's plane (world units, x right, y up)
  vec4 shape;       // half width (world units), shape, seed, pixels per world unit at the foot
  vec4 extra;       // distance drawn towards the eye (world units)
};
layout(std430, binding = 2) readonly buffer Marks {
  Mark marks[];
};
uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform vec3 u_right;  // the camera's right, level
out vec2 v_local;        // along and across the mark, in half widths
flat out float v_length; // a → b, in half widths
flat out float v_ink;
flat out int v_shape;
flat out float v_seed;
flat out float v_pixel;  // one pixel, in half widths

// A mark narrower than this many pixels is drawn at it with its ink thinned to match: no
// sub-pixel marks that flicker, and the same ink on the paper.
const float kLeastHalfWidthPx = 0.6;

void main() {
  Mark m = marks[gl_VertexID / 6];
  const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
  vec2 c = corners[gl_VertexID % 6];
  float half_width = m.shape.x, per_unit = m.shape.w, ink = m.anchor_ink.w;
  float px = half_width * per_unit;
  if (px < kLeastHalfWidthPx) {
    ink *= px / kLeastHalfWidthPx;
    half_width = kLeastHalfWidthPx / per_unit;
  }
  vec2 d = m.ab.zw - m.ab.xy;
  float len = length(d);
  vec2 dir = len > 1e-6 * half_width ? d / len : vec2(0.0, 1.0);
  vec2 across_dir = vec2(-dir.y, dir.x);
  float room = half_width + 1.0 / per_unit;
  float along = mix(-room, len + room, c.x), across = mix(-room, room, c.y);
  vec2 local = m.ab.xy + dir * along + across_dir * across;
  vec3 world = m.anchor_ink.xyz + u_right * local.x + vec3(0.0, 0.0, local.y);
  // Towards the eye along the vertex's own ray: the same place on screen, in front of the
  // ground the element stands on.
  vec3 ray = world - u_eye;
  world = u_eye + ray * max(1.0 - m.extra.x / max(length(ray), 1e-30), 0.5);
  gl_Position = u_view_projection * vec4(world, 1.0);
  v_local = vec2(along, across) / half_width;
  v_length = len / half_width;
  v_ink = ink;
  v_shape = int(m.shape.y + 0.5);
  v_seed = m.shape.z;
  v_pixel = 1.0 / (half_width * per_unit);
}
