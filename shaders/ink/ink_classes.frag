#version 450 core
// The ink pass's three kinds of pixel, as depth for its depth test (ink_pass.cpp), so that a
// fragment pass shades each kind with its own program and a software rasteriser, which runs
// both sides of a branch for a whole group of pixels, skips a group no pixel of which is of
// the kind drawn: 0 a surface to shade, 0.5 a bare one (the lines pass found that the
// atmosphere leaves nothing of it: a dissolved border), 1 the background (which the lines
// pass left at its clear value, alpha 1; one image load, not a depth fetch as well).
layout(rgba16, binding = 4) readonly uniform image2D u_presence_noise;

void main() {
  vec4 presence_noise = imageLoad(u_presence_noise, ivec2(gl_FragCoord.xy));
  gl_FragDepth = presence_noise.a > 0.5 ? 1.0 : (presence_noise.r > 0.0 ? 0.0 : 0.5);
}
