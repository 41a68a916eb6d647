#version 450 core
// Ink diffusion, step 1: ink of the rendered picture, I = clamp(1 − lum / lum(paper), 0, 1).
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D u_colour;
layout(r32f, binding = 0) writeonly uniform image2D u_ink;
uniform vec3 u_paper;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_ink)))) return;
  const vec3 weights = vec3(0.2126, 0.7152, 0.0722);
  float lum = dot(texelFetch(u_colour, p, 0).rgb, weights);
  float ink = clamp(1.0 - lum / max(dot(u_paper, weights), 1e-6), 0.0, 1.0);
  imageStore(u_ink, p, vec4(ink));
}
