#version 450 core
// The cached layer of the static objects' brush strokes laid over the picture (seed 002's
// render states). The layer holds premultiplied ink; a texel is left out where an animated
// object now stands in front of the nearest static surface within a stroke's reach (a
// stroke overruns the silhouette it follows by up to half its width).
layout(binding = 0) uniform sampler2D u_layer;
layout(binding = 1) uniform sampler2D u_static_depth;
layout(binding = 2) uniform sampler2D u_depth;
uniform int u_reach;  // pixels
out vec4 frag;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 ink = texelFetch(u_layer, p, 0);
  if (ink.a <= 0.0) discard;
  ivec2 last = textureSize(u_layer, 0) - 1;
  float nearest = texelFetch(u_static_depth, p, 0).r;
  for (int i = 0; i < 4; ++i) {
    ivec2 o = ivec2(i == 0 ? u_reach : (i == 1 ? -u_reach : 0), i == 2 ? u_reach : (i == 3 ? -u_reach : 0));
    nearest = min(nearest, texelFetch(u_static_depth, clamp(p + o, ivec2(0), last), 0).r);
  }
  if (texelFetch(u_depth, p, 0).r < nearest) discard;
  frag = ink;
}
