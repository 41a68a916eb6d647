#version 450 core
// The elements pass's first step (libs/render/src/elements_pass.cpp): one thread per element
// of an object. It places the element in the world, culls what is out of view, weighs the
// levels of detail by its height on screen (elements::levelWeights), finds the ink the
// distance fade, the mist and the border leave at its foot (atmosphere.cpp's presence(), the
// noise at its mean), and appends one entry per mark of the active levels for
// elements.vert to draw; the count goes into the indirect draw's vertex count.
layout(local_size_x = 64) in;

struct Instance {
  vec4 position_size;  // uploaded coordinates of its object; height (trees) or size factor (dots)
  vec4 lean_seed;      // lean (radians), seed in [0, 1), mirrored (0 or 1), template index
};
struct FrameInstance {
  vec4 anchor_ppu;  // foot (world), pixels per world unit there
  vec4 look;        // distance drawn towards the eye, seed, mirrored, lean
};
struct Entry {
  uint instance;  // into frame_instances
  uint mark;      // into the templates' marks
  float ink;
  float size;  // world units per template unit
};
layout(std430, binding = 0) readonly buffer Instances {
  Instance instances[];
};
// Per template: where its marks of each level group begin (far only, middle only, middle and
// near, near only) and end; a moss dot's one mark is in the far group and drawn at every level.
layout(std430, binding = 1) readonly buffer Templates {
  ivec4 group_start[];  // pairs: [2t] = starts of the four groups, [2t + 1].x = the end
};
layout(std430, binding = 3) writeonly buffer Frame {
  FrameInstance frame_instances[];
};
layout(std430, binding = 4) writeonly buffer Entries {
  Entry entries[];
};
layout(std430, binding = 5) buffer Indirect {
  uint vertex_count, instance_count, first_vertex, base_instance;
};

uniform mat4 u_model;  // uploaded coordinates to world
uniform mat4 u_view_projection;
uniform vec3 u_eye;
uniform float u_near;
uniform float u_pixels_at_1;  // pixels per world unit at distance 1
uniform float u_per_1024;     // picture height / 1024
uniform float u_height_px;
uniform float u_scale;        // of u_model (cube root of its determinant)
uniform uint u_first;         // this object's first element in frame_instances
uniform uint u_count;
uniform uint u_capacity;      // entries
uniform float u_tree_ink, u_dot_ink, u_dot_px;
uniform float u_least_far_px;  // a far tree's dab is at least this wide (pixels at 1024)
uniform uint u_dot_template;
// Atmosphere and border.
uniform float u_fade;
uniform vec2 u_fade_range;
uniform vec3 u_mist;  // density, z where it is full, thinning band (0: no mist)
uniform vec4 u_to_model_x, u_to_model_y;
uniform vec2 u_half_extent;
uniform float u_border_width;  // 0: no border
uniform float u_border_roughness;

float presence(vec3 world) {
  float f = 1.0 - u_fade * smoothstep(u_fade_range.x, u_fade_range.y, distance(world, u_eye));
  if (u_mist.x > 0.0) f *= 1.0 - u_mist.x * (1.0 - smoothstep(0.0, 1.0, (world.z - u_mist.y) / u_mist.z));
  if (u_border_width > 0.0) {
    vec4 w = vec4(world, 1.0);
    vec2 m = vec2(dot(u_to_model_x, w), dot(u_to_model_y, w));
    vec2 inside = u_half_extent - abs(m);
    f *= smoothstep(0.0, 1.0, min(inside.x, inside.y) / u_border_width - 0.5 * u_border_roughness);
  }
  return clamp(f, 0.0, 1.0);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= u_count) return;
  Instance e = instances[i];
  vec3 world = (u_model * vec4(e.position_size.xyz, 1.0)).xyz;
  vec4 clip = u_view_projection * vec4(world, 1.0);
  if (clip.w <= u_near) return;
  float ppu = u_pixels_at_1 / clip.w;
  uint t = uint(e.lean_seed.w + 0.5);
  bool dot = t == u_dot_template;
  float height = dot ? u_dot_px * u_per_1024 * e.position_size.w / ppu : e.position_size.w * u_scale;
  // In view, with room for the element above its foot.
  float reach = 2.0 * height * ppu / u_height_px + 0.05;
  vec2 ndc = clip.xy / clip.w;
  if (abs(ndc.x) > 1.0 + reach || ndc.y > 1.05 || ndc.y < -1.0 - reach) return;
  float here = presence(world);
  if (here < 0.004) return;

  float ink = dot ? u_dot_ink * here : u_tree_ink * here;
  float px = height * ppu / u_per_1024;
  float middle_in = dot ? 0.0 : smoothstep(8.0, 14.0, px), near_in = smoothstep(28.0, 44.0, px);
  vec3 w = vec3(1.0 - middle_in, middle_in * (1.0 - near_in), middle_in * near_in);
  // A far tree stays a dab a painter can see: its far marks grow to the least width.
  float far_size = height * max(1.0, u_least_far_px / max(0.3 * px, 1e-9));
  ivec4 g = group_start[2 * t];
  int end = group_start[2 * t + 1].x;
  // The active levels are adjacent, so their marks are one run of the groups.
  int lo = w.x > 0.0 ? g.x : (w.y > 0.0 ? g.y : g.z);
  int hi = w.z > 0.0 ? end : (w.y > 0.0 ? g.w : g.y);
  if (dot) {
    lo = g.x;
    hi = end;
  }
  int count = hi - lo;
  if (count <= 0) return;
  uint slot = u_first + i;
  frame_instances[slot].anchor_ppu = vec4(world, ppu);
  frame_instances[slot].look =
      vec4(min(dot ? 2.0 * height : 0.5 * height, 0.25 * clip.w), e.lean_seed.y, e.lean_seed.z, e.lean_seed.x);
  uint base = atomicAdd(vertex_count, 6u * uint(count)) / 6u;
  for (int k = 0; k < count && base + uint(k) < u_capacity; ++k) {
    int m = lo + k;
    // Which levels the mark belongs to: its group.
    float weight = dot ? 1.0 : (m < g.y ? w.x : (m < g.z ? w.y : (m < g.w ? w.y + w.z : w.z)));
    bool far_only = !dot && m < g.y;
    entries[base + uint(k)] = Entry(slot, uint(m), ink * weight, far_only ? far_size : height);
  }
}
