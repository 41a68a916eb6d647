#version 450 core
// Ink diffusion, step 1: ink of the rendered picture, I = clamp(1 − lum / lum(paper), 0, 1),
// and what each pixel may absorb per boundary iteration: I_p / n · absorbency, 0 on the
// strokes (I > threshold), which do not absorb. Both are stored two pixels to a texel
// (pixel x in channel x & 1 of texel x / 2; the unused half of an odd width's last texel
// holds 0). One invocation per texel column (two pixel columns) and STRIP_ROWS rows (on
// llvmpipe a loop is cheaper than an invocation per pixel). It also marks, per block of
// BLOCK_SIZE² pixels, where ink lies above the residual or a stroke is (u_seeds: where the
// boundary iterations start, and the main region's rings, which lie within d of a stroke;
// nothing changes farther than n + d from a mark) and where strokes are (u_strokes: the
// main region's sweeps skip blocks farther than d from any).
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
#include "ink_diffusion_ink.glsl"
layout(rgba8, binding = 2) readonly uniform image2D u_colour;
layout(binding = 1) uniform sampler2D u_absorbency;  // tiled over the picture
layout(rg32f, binding = 0) writeonly uniform image2D u_ink;
layout(rg32f, binding = 1) writeonly uniform image2D u_capacity;
uniform vec3 u_paper;
uniform vec2 u_absorbency_map;  // absorbency = clamp(y + x · texel, 0, 1)
uniform float u_absorb;         // I_p / n
uniform float u_threshold;
layout(r8ui, binding = 3) writeonly uniform uimage2D u_seeds;
layout(r8ui, binding = 4) writeonly uniform uimage2D u_strokes;
uniform float u_residual;
uniform ivec2 u_lo, u_hi;  // the window computed (pixels; u_lo on whole work-group areas)

void main() {
  const ivec2 size = u_hi;
  int x = u_lo.x + 2 * int(gl_GlobalInvocationID.x);  // the texel's first column
  if (x >= size.x) return;
  const bool pair = x + 1 < imageSize(u_colour).x;
  // The tile's columns, by float division: exact for integers below 2^23, and vectorises
  // where an integer % does not.
  const vec2 tile = vec2(textureSize(u_absorbency, 0));
  const ivec2 tx = ivec2(vec2(x, x + 1) - tile.x * floor(vec2(x, x + 1) / tile.x));
  const int y0 = u_lo.y + int(gl_WorkGroupID.y) * STRIP_ROWS, y1 = min(y0 + STRIP_ROWS, size.y);
  bool seed = false, stroke = false;
  for (int y = y0; y < y1; ++y) {
    int ty = int(float(y) - tile.y * floor(float(y) / tile.y));
    vec2 ink, capacity;
    for (int i = 0; i < 2; ++i) {
      ink[i] = inkOf(imageLoad(u_colour, ivec2(x + i, y)).rgb, u_paper);
      float a = clamp(u_absorbency_map.y + u_absorbency_map.x * texelFetch(u_absorbency, ivec2(tx[i], ty), 0).r, 0.0, 1.0);
      capacity[i] = ink[i] > u_threshold ? 0.0 : u_absorb * a;
    }
    if (!pair) ink.y = capacity.y = 0.0;  // no pixel there: no ink, no capacity
    ivec2 t = ivec2(x / 2, y);
    imageStore(u_ink, t, vec4(ink, 0.0, 0.0));
    imageStore(u_capacity, t, vec4(capacity, 0.0, 0.0));
    seed = seed || any(greaterThan(ink, vec2(min(u_residual, u_threshold))));
    stroke = stroke || any(greaterThan(ink, vec2(u_threshold)));
    if (((y + 1) & (BLOCK_SIZE - 1)) == 0 || y + 1 == y1) {  // the block's last row
      ivec2 block = ivec2(x, y) / BLOCK_SIZE;  // both columns lie in one block (BLOCK_SIZE is even)
      if (seed) imageStore(u_seeds, block, uvec4(1u));
      if (stroke) imageStore(u_strokes, block, uvec4(1u));
      seed = stroke = false;
    }
  }
}
