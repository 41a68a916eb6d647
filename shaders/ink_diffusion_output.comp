#version 450 core
// Ink diffusion, last step: the picture with the ink change painted in,
// c − paper · (I_after − I_before); unchanged pixels keep their colour.
layout(local_size_x = 16, local_size_y = 16) in;
layout(binding = 0) uniform sampler2D u_colour;
layout(r32f, binding = 0) readonly uniform image2D u_before;
layout(r32f, binding = 1) readonly uniform image2D u_after;
layout(rgba8, binding = 2) writeonly uniform image2D u_out;
uniform vec3 u_paper;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_out)))) return;
  vec3 c = texelFetch(u_colour, p, 0).rgb;
  float change = imageLoad(u_after, p).r - imageLoad(u_before, p).r;
  imageStore(u_out, p, vec4(clamp(c - u_paper * change, 0.0, 1.0), 1.0));
}
