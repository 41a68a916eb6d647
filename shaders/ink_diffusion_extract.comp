#version 450 core
// Ink diffusion, step 1: ink of the rendered picture, I = clamp(1 − lum / lum(paper), 0, 1),
// and what each pixel may absorb per boundary iteration: I_p / n · absorbency, 0 on the
// strokes (I > threshold), which do not absorb. One invocation per column and STRIP_ROWS
// rows (on llvmpipe a loop is cheaper than an invocation per pixel). It also marks, per
// block of BLOCK_SIZE² pixels, where ink lies above the residual (u_seeds: where the
// boundary iterations start, with the main region's rings, which lie within d of a
// stroke) and where strokes are (u_strokes: the main region's sweeps skip blocks farther
// than d from any).
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
#include "ink_diffusion_ink.glsl"
layout(rgba8, binding = 2) readonly uniform image2D u_colour;
layout(binding = 1) uniform sampler2D u_absorbency;  // tiled over the picture
layout(r32f, binding = 0) writeonly uniform image2D u_ink;
layout(r32f, binding = 1) writeonly uniform image2D u_capacity;
uniform vec3 u_paper;
uniform vec2 u_absorbency_map;  // absorbency = clamp(y + x · texel, 0, 1)
uniform float u_absorb;         // I_p / n
uniform float u_threshold;
layout(r8ui, binding = 3) writeonly uniform uimage2D u_seeds;
layout(r8ui, binding = 4) writeonly uniform uimage2D u_strokes;
uniform float u_residual;

void main() {
  ivec2 size = imageSize(u_ink);
  int x = int(gl_GlobalInvocationID.x);
  if (x >= size.x) return;
  // The tile's column, by float division: exact for integers below 2^23, and vectorises
  // where an integer % does not.
  const vec2 tile = vec2(textureSize(u_absorbency, 0));
  const int tx = int(float(x) - tile.x * floor(float(x) / tile.x));
  const int y0 = int(gl_WorkGroupID.y) * STRIP_ROWS, y1 = min(y0 + STRIP_ROWS, size.y);
  bool seed = false, stroke = false;
  for (int y = y0; y < y1; ++y) {
    ivec2 p = ivec2(x, y);
    float ink = inkOf(imageLoad(u_colour, p).rgb, u_paper);
    imageStore(u_ink, p, vec4(ink));
    int ty = int(float(y) - tile.y * floor(float(y) / tile.y));
    float a = clamp(u_absorbency_map.y + u_absorbency_map.x * texelFetch(u_absorbency, ivec2(tx, ty), 0).r, 0.0, 1.0);
    imageStore(u_capacity, p, vec4(ink > u_threshold ? 0.0 : u_absorb * a));
    seed = seed || ink > u_residual;
    stroke = stroke || ink > u_threshold;
    if (((y + 1) & (BLOCK_SIZE - 1)) == 0 || y + 1 == y1) {  // the block's last row
      if (seed) imageStore(u_seeds, p / BLOCK_SIZE, uvec4(1u));
      if (stroke) imageStore(u_strokes, p / BLOCK_SIZE, uvec4(1u));
      seed = stroke = false;
    }
  }
}
