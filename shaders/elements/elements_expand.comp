#version 450 core
// The elements pass's first step (libs/render/src/passes/elements_pass.cpp): one thread per element
// of an object. It places the element in the world, culls what is out of view, weighs the
// levels of detail by its height on screen (elements::levelWeights), finds the ink the
// distance fade, the mist and the border leave at its foot (atmosphere.cpp's presence(),
// the mist's noise at its mean; the border's taken later: borderInk), and appends one entry
// per mark of the active levels for elements.vert to draw; the count goes into the indirect
// draw's instance count.
layout(local_size_x = 64) in;

struct Instance {
  vec4 position_size;  // uploaded coordinates of its object; height (trees) or size factor (dots)
  vec4 lean_seed;      // lean (radians), seed in [0, 1), mirrored (0 or 1), template index
};
struct FrameInstance {
  vec4 anchor_ppu;  // foot (world), pixels per world unit there
  vec4 look;        // distance drawn towards the eye, seed, cosine and sine of 2π seed
  vec4 turn;        // where the template's x and y axes go: mirrored, then leant
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
  uint vertex_count, instance_count, first_vertex, base_instance;  // a strip of 4, one instance a mark
};

uniform mat4 u_model;  // uploaded coordinates to world
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
uniform float u_near;
uniform float u_pixels_at_1;  // pixels per world unit at distance 1
uniform float u_per_1024;     // picture height / 1024
uniform float u_height_px;
uniform float u_scale;        // of u_model (cube root of its determinant)
uniform uint u_first;         // this object's first element in instances and frame_instances
uniform uint u_count;
uniform uint u_capacity;      // entries
uniform float u_tree_ink, u_dot_ink, u_dot_px;
uniform vec4 u_level_bands;    // elements::kLevelBands: far → middle, middle → near (pixels at 1024)
uniform float u_least_far_px;  // a far tree's dab is at least this wide (pixels at 1024)
uniform uint u_dot_template;
// Atmosphere and border.
uniform vec4 u_to_model_x, u_to_model_y;
uniform vec2 u_half_extent;
uniform float u_border_width;  // 0: no border
uniform float u_border_roughness;
layout(r8, binding = 0) readonly uniform image2D u_value_noise;  // the border's noise (with a border)
// What stands on this object (a hut, a pagoda, a boulder: objects grounded on it), at most
// kMaxClearings of them: its centre (world) and its horizontal radius. No tree stands within
// that radius and half its own height of one, nor in front of it, between it and the eye,
// as far as the tree's crown would reach up over it on the picture: a building stands in a
// clearing, flanked by trees instead of behind a trunk. Moss dots may grow to its foot.
const int kMaxClearings = MAX_CLEARINGS;  // elements_pass.cpp's, defined when built
uniform int u_clearings;
uniform vec4 u_clearing[kMaxClearings];

bool inAClearing(vec3 foot, float height) {
  for (int k = 0; k < u_clearings; ++k) {
    vec3 c = u_clearing[k].xyz;
    vec2 to_eye = u_eye.xy - c.xy;
    float level = length(to_eye);
    vec2 ahead = level > 1e-6 ? to_eye / level : vec2(0.0);
    // A tree this far in front of the building covers it up to its top: its height over the
    // tangent of the eye's elevation seen from the building, at most four heights.
    float reach = min(height * level / max(u_eye.z - c.z, 0.25 * level), 4.0 * height);
    vec2 d = foot.xy - c.xy;
    vec2 nearest = c.xy + ahead * clamp(dot(d, ahead), 0.0, reach);
    if (distance(foot.xy, nearest) < u_clearing[k].w + 0.5 * height) return true;
  }
  return false;
}
#include "border_noise.glsl"

// What the distance fade and the mist leave at a foot (world).
float presence(vec3 world) {
  float far = smoothstep(u_fade_range.x, u_fade_range.y, distance(world, u_eye));
  float f = 1.0 - u_fade * far;
  if (u_mist.x > 0.0)
    f *= 1.0 - u_mist.x * mix(u_mist_near, 1.0, far) * (1.0 - smoothstep(0.0, 1.0, (world.z - u_mist.y) / u_mist.z));
  return clamp(f, 0.0, 1.0);
}

// What the dissolving border leaves of an element at a foot (world), `near` the share of its
// near level of detail (a tree drawn large, with its full brushwork). Taken from what it
// leaves of the ground there, later than the ground: full ink where the ground keeps half
// of its own, none where it keeps a twentieth; the ground washes out over the whole band,
// but a painter keeps a tree dark until near the edge. Small elements (far dabs, moss dots)
// read the ground's ragged edge itself (the ink pass's noise), so none stands on the paper
// beyond it; a large tree reads the band at the noise's mean, so the trees of a bank that
// dissolves at its front stay its darkest marks, their feet in the mist.
float borderInk(vec3 world, float near) {
  if (u_border_width <= 0.0) return 1.0;
  vec4 w = vec4(world, 1.0);
  vec2 m = vec2(dot(u_to_model_x, w), dot(u_to_model_y, w));
  float mean = smoothstep(0.0, 1.0, borderDepth(m, u_half_extent, u_border_width) - 0.5 * u_border_roughness);
  float ragged = borderLeft(m, u_half_extent, u_border_width, u_border_roughness);
  return smoothstep(0.05, 0.5, mix(ragged, mean, near));
}

// The work group's marks are appended with one global atomic: each element takes its place
// within the group from a shared counter first.
shared uint group_count, group_base;

// How many marks element i draws (0 when it is out of view), and what they need.
int marks(uint i, out vec3 world, out float ppu, out float height, out float ink, out vec3 w, out float far_size,
          out int lo, out uint t, out bool dot, out float bias) {
  if (i >= u_count) return 0;
  Instance e = instances[u_first + i];
  world = (u_model * vec4(e.position_size.xyz, 1.0)).xyz;
  if (world.z < u_water.x) return 0;  // nothing grows under water (u_water.x: the lowest float without water)
  vec4 clip = u_view_projection * vec4(world, 1.0);
  if (clip.w <= u_near) return 0;
  ppu = u_pixels_at_1 / clip.w;
  t = uint(e.lean_seed.w + 0.5);
  dot = t == u_dot_template;
  height = dot ? u_dot_px * u_per_1024 * e.position_size.w / ppu : e.position_size.w * u_scale;
  if (!dot && inAClearing(world, height)) return 0;
  // In view, with room for the element above its foot.
  float reach = 2.0 * height * ppu / u_height_px + 0.05;
  vec2 ndc = clip.xy / clip.w;
  if (abs(ndc.x) > 1.0 + reach || ndc.y > 1.05 || ndc.y < -1.0 - reach) return 0;
  float px = height * ppu / u_per_1024;
  float middle_in = dot ? 0.0 : smoothstep(u_level_bands.x, u_level_bands.y, px);
  float near_in = smoothstep(u_level_bands.z, u_level_bands.w, px);
  float here = presence(world) * borderInk(world, dot ? 0.0 : near_in);
  if (here < 0.004) return 0;
  ink = dot ? u_dot_ink * here : u_tree_ink * here;
  w = vec3(1.0 - middle_in, middle_in * (1.0 - near_in), middle_in * near_in);
  // A far tree stays a dab a painter can see: its far marks grow to the least width.
  far_size = height * max(1.0, u_least_far_px / max(0.3 * px, 1e-9));
  bias = min(dot ? 2.0 * height : 0.5 * height, 0.25 * clip.w);
  ivec4 g = group_start[2 * t];
  int end = group_start[2 * t + 1].x;
  // The active levels are adjacent, so their marks are one run of the groups.
  lo = w.x > 0.0 ? g.x : (w.y > 0.0 ? g.y : g.z);
  int hi = w.z > 0.0 ? end : (w.y > 0.0 ? g.w : g.y);
  if (dot) {
    lo = g.x;
    hi = end;
  }
  return max(hi - lo, 0);
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (gl_LocalInvocationIndex == 0u) group_count = 0u;
  barrier();
  vec3 world, w;
  float ppu, height, ink, far_size, bias;
  int lo;
  uint t;
  bool dot;
  int count = marks(i, world, ppu, height, ink, w, far_size, lo, t, dot, bias);
  uint local = count > 0 ? atomicAdd(group_count, uint(count)) : 0u;
  barrier();
  if (gl_LocalInvocationIndex == 0u && group_count > 0u) group_base = atomicAdd(instance_count, group_count);
  barrier();
  if (count == 0) return;
  Instance e = instances[u_first + i];
  uint slot = u_first + i;
  frame_instances[slot].anchor_ppu = vec4(world, ppu);
  float seed_angle = 6.2831853 * e.lean_seed.y;
  frame_instances[slot].look = vec4(bias, e.lean_seed.y, cos(seed_angle), sin(seed_angle));
  // Columns: where x and y go, clockwise for a positive lean; x negated first when mirrored.
  float cl = cos(e.lean_seed.x), sl = sin(e.lean_seed.x), mirror = e.lean_seed.z > 0.5 ? -1.0 : 1.0;
  frame_instances[slot].turn = vec4(mirror * vec2(cl, -sl), sl, cl);
  ivec4 g = group_start[2 * t];
  uint base = group_base + local;
  for (int k = 0; k < count && base + uint(k) < u_capacity; ++k) {
    int m = lo + k;
    // Which levels the mark belongs to: its group.
    float weight = dot ? 1.0 : (m < g.y ? w.x : (m < g.z ? w.y : (m < g.w ? w.y + w.z : w.z)));
    bool far_only = !dot && m < g.y;
    entries[base + uint(k)] = Entry(slot, uint(m), ink * weight, far_only ? far_size : height);
  }
}
