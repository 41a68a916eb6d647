#version 450 core
// The elements' marks (libs/render/src/passes/elements_pass.cpp): one instance of a four-vertex strip
// per entry that elements_expand.comp appended, each a quad around the template mark's segment a → b (round
// caps and a pixel of room for the edge's smoothing) on an upright billboard through the
// element's foot that faces the camera.
struct FrameInstance {
  vec4 anchor_ppu;  // foot (world), pixels per world unit there
  vec4 look;        // distance drawn towards the eye, seed, cosine and sine of 2π seed
  vec4 turn;        // where the template's x and y axes go: mirrored, then leant
};
struct Entry {
  uint instance;
  uint mark;
  float ink;
  float size;  // world units per template unit
};
struct Mark {
  vec4 ab;     // ends, in units of the element's height (x right, y up from the foot)
  vec4 shape;  // width, ink, shape, levels
};
layout(std430, binding = 2) readonly buffer Marks {
  Mark marks[];
};
layout(std430, binding = 3) readonly buffer Frame {
  FrameInstance frame_instances[];
};
layout(std430, binding = 4) readonly buffer Entries {
  Entry entries[];
};
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
uniform vec3 u_right;  // the camera's right, level
uniform uint u_capacity;
out vec2 v_local;         // along and across the mark, in half widths
flat out float v_length;  // a → b, in half widths
flat out float v_ink;
flat out int v_shape;
flat out float v_seed;
flat out float v_pixel;  // one pixel, in half widths
flat out vec2 v_turn;

// A mark narrower than this many pixels is drawn at it with its ink thinned to match: no
// sub-pixel marks that flicker, and the same ink on the paper.
const float kLeastHalfWidthPx = 0.6;

void main() {
  uint k = uint(gl_InstanceID);
  if (k >= u_capacity) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // outside the view: nothing drawn
    return;
  }
  Entry e = entries[k];
  FrameInstance f = frame_instances[e.instance];
  Mark m = marks[e.mark];
  vec2 c = vec2(gl_VertexID & 1, gl_VertexID >> 1);  // a strip of four corners
  // The template's mark, mirrored, leant and scaled to the element.
  mat2 turn = mat2(f.turn.xy, f.turn.zw);
  vec2 a = e.size * (turn * m.ab.xy), b = e.size * (turn * m.ab.zw);
  float per_unit = f.anchor_ppu.w, ink = min(e.ink * m.shape.y, 1.0);
  float half_width = 0.5 * e.size * m.shape.x;
  float px = half_width * per_unit;
  if (px < kLeastHalfWidthPx) {
    ink *= px / kLeastHalfWidthPx;
    half_width = kLeastHalfWidthPx / per_unit;
  }
  vec2 d = b - a;
  float len = length(d);
  vec2 dir = len > 1e-6 * half_width ? d / len : vec2(0.0, 1.0);
  vec2 across_dir = vec2(-dir.y, dir.x);
  float room = half_width + 1.0 / per_unit;
  float along = mix(-room, len + room, c.x), across = mix(-room, room, c.y);
  vec2 local = a + dir * along + across_dir * across;
  vec3 world = f.anchor_ppu.xyz + u_right * local.x + vec3(0.0, 0.0, local.y);
  // Towards the eye along the vertex's own ray: the same place on screen, in front of the
  // ground the element stands on.
  vec3 ray = world - u_eye;
  world = u_eye + ray * max(1.0 - f.look.x / max(length(ray), 1e-30), 0.5);
  gl_Position = u_view_projection * vec4(world, 1.0);
  v_local = vec2(along, across) / half_width;
  v_length = len / half_width;
  v_ink = ink;
  v_shape = int(m.shape.z + 0.5);
  v_seed = f.look.y;
  v_pixel = 1.0 / (half_width * per_unit);
  v_turn = f.look.zw;
}
