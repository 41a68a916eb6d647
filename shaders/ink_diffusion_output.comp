#version 450 core
// Ink diffusion, last step: the picture with the ink change painted in,
// c − paper · (I_after − I_before); unchanged pixels keep their colour. CANVAS: then the
// paper's grain, × (1 + contrast · canvas noise), over everything.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D u_colour;
layout(r32f, binding = 0) readonly uniform image2D u_before;
layout(r32f, binding = 1) readonly uniform image2D u_after;
layout(rgba8, binding = 2) writeonly uniform image2D u_out;
uniform vec3 u_paper;
#ifdef CANVAS
layout(binding = 1) uniform sampler2D u_canvas;
uniform float u_canvas_contrast;
#endif

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_out)))) return;
  vec3 c = texelFetch(u_colour, p, 0).rgb;
  float change = imageLoad(u_after, p).r - imageLoad(u_before, p).r;
  c -= u_paper * change;
#ifdef CANVAS
  c *= 1.0 + u_canvas_contrast * texelFetch(u_canvas, p, 0).r;
#endif
  imageStore(u_out, p, vec4(clamp(c, 0.0, 1.0), 1.0));
}
