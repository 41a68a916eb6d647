#version 450 core
// Ink diffusion, last step: the picture with the ink change painted in,
// c − paper · (I_after − I_before); unchanged pixels keep their colour, and alpha passes
// through. One invocation per pair of columns (a texel of u_after, which holds two pixels:
// x in channel x & 1) and STRIP_ROWS rows.
//
// CANVAS: the paper, × (1 + contrast · grain)(1 + marks), then goes over everything,
// so every pixel is written. Without it the pass has copied the picture into u_out first,
// and only the pixels whose ink changed are written: none in the areas u_active leaves out
// (no ink above the residual and no stroke within n + d), and an RGBA8 store costs
// llvmpipe more than the copy.
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
#include "ink_diffusion_ink.glsl"
layout(rgba8, binding = 3) readonly uniform image2D u_colour;
layout(rg32f, binding = 1) readonly uniform image2D u_after;
layout(rgba8, binding = 2) writeonly uniform image2D u_out;
uniform vec3 u_paper;
#ifdef CANVAS
layout(rg16f, binding = 4) readonly uniform image2D u_canvas;  // grain, marks
uniform float u_canvas_contrast;
#else
layout(r8ui, binding = 5) readonly uniform uimage2D u_active;  // one texel per AREA_W × AREA_H pixels
#endif
uniform ivec2 u_lo, u_hi;            // the window computed (pixels; u_lo on whole work-group areas)
uniform ivec2 u_store_lo, u_store_hi;  // the pixels written: the window less its margin

void main() {
  const ivec2 size = u_hi;
  int x = u_lo.x + 2 * int(gl_GlobalInvocationID.x);  // the pair's first column
  if (x >= size.x) return;
  const int y0 = u_lo.y + int(gl_WorkGroupID.y) * STRIP_ROWS, y1 = min(y0 + STRIP_ROWS, size.y);
#ifndef CANVAS
  // The pair lies in one area (AREA_W is even) and the strip in one row of areas.
  if (imageLoad(u_active, ivec2(x / AREA_W, y0 / AREA_H)).r == 0u) return;
#endif
  const int columns = min(2, size.x - x);
  for (int y = y0; y < y1; ++y) {
    vec2 after = imageLoad(u_after, ivec2(x / 2, y)).rg;
    for (int i = 0; i < columns; ++i) {
      ivec2 p = ivec2(x + i, y);
      if (any(lessThan(p, u_store_lo)) || any(greaterThanEqual(p, u_store_hi))) continue;
      vec4 colour = imageLoad(u_colour, p);
      vec3 c = colour.rgb;
      float before = inkOf(c, u_paper);
#ifndef CANVAS
      if (after[i] == before) continue;  // the copy holds it
#endif
      c -= u_paper * (after[i] - before);
#ifdef CANVAS
      vec2 paper = imageLoad(u_canvas, p).rg;
      c *= (1.0 + u_canvas_contrast * paper.r) * (1.0 + paper.g);
#endif
      imageStore(u_out, p, vec4(clamp(c, 0.0, 1.0), colour.a));
    }
  }
}
