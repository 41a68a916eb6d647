#version 450 core
// Evaluates one wet-stroke group (ink_marks.glsl's washGroup) at given points, for the test
// that holds its shortcut, the two strokes nearest a point layered, to the brute force: every
// stroke of the group layered. Also the darkest single stroke there, to show where strokes
// overlap.
#include "ink_marks.glsl"
layout(local_size_x = 64) in;

// x, y: the point's offset from the group's centre (cells); z: breadth; w: the group's number.
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
// x: washGroup; y: all strokes layered; z: the darkest single stroke; w: 2m + 1.
layout(std430, binding = 1) writeonly buffer Values { vec4 values[]; };
uniform int u_count;

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= u_count) return;
  vec4 q = points[i];
  uint h = cellHash(uvec2(uint(q.w), 0x5bd1e995u)), seed = 12345u;
  vec4 a = unpack4(h);
  a.z = 0.0;  // every group kept: density 1 beats its threshold
  vec2 dir = vec2(0.0, -1.0);
  vec4 b;
  float along, across, hair, gap, slant;
  int m;
  washFrame(q.xy, dir, h, q.z, seed, b, along, across, hair, m, gap, slant);
  float all_layered = 0.0, darkest = 0.0;
  for (int j = 0; j <= 2 * m; ++j) {
    float one = washStroke(j, along, across, hair, m, gap, q.z, slant, a, b);
    all_layered += (1.0 - all_layered) * one;
    darkest = max(darkest, one);
  }
  values[i] = vec4(washGroup(q.xy, dir, h, a, 1.0, q.z, seed), all_layered, darkest, float(2 * m + 1));
}
