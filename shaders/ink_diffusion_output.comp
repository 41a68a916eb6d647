#version 450 core
// Ink diffusion, last step: the picture with the ink change painted in,
// c − paper · (I_after − I_before); unchanged pixels keep their colour. CANVAS: then the
// paper's grain, × (1 + contrast · canvas noise), over everything. One invocation per
// column and STRIP_ROWS rows.
layout(local_size_x = LINE_GROUP) in;  // invocations (rows or columns) per work group
#include "ink_diffusion_ink.glsl"
layout(rgba8, binding = 3) readonly uniform image2D u_colour;
layout(r32f, binding = 1) readonly uniform image2D u_after;
layout(rgba8, binding = 2) writeonly uniform image2D u_out;
uniform vec3 u_paper;
#ifdef CANVAS
layout(r32f, binding = 4) readonly uniform image2D u_canvas;
uniform float u_canvas_contrast;
#endif

void main() {
  ivec2 size = imageSize(u_out);
  int x = int(gl_GlobalInvocationID.x);
  if (x >= size.x) return;
  const int y0 = int(gl_WorkGroupID.y) * STRIP_ROWS, y1 = min(y0 + STRIP_ROWS, size.y);
  for (int y = y0; y < y1; ++y) {
    ivec2 p = ivec2(x, y);
    vec3 c = imageLoad(u_colour, p).rgb;
    c -= u_paper * (imageLoad(u_after, p).r - inkOf(c, u_paper));
#ifdef CANVAS
    c *= 1.0 + u_canvas_contrast * imageLoad(u_canvas, p).r;
#endif
    imageStore(u_out, p, vec4(clamp(c, 0.0, 1.0), 1.0));
  }
}
