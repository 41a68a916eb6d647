#version 450 core
// Rice paper's mottle for the `tiles` canvas, drawn into a small image with one texel per
// u_cell × u_cell pixels of the view (its centre's value), which canvas_tiles.frag reads
// bilinearly: the mottle changes over about a hundred pixels, so at the default cell the
// reads stay within 2 % of its contrast on average of computing it at every pixel
// (CanvasGl.TheMottleImageIsWhatEachPixelWouldCompute), for a sixtieth of the work.
#include "canvas_lattice.glsl"

uniform float u_cell;  // pixels of the view per texel
layout(location = 0) out float o_mottle;

void main() {
  vec2 ndc = gl_FragCoord.xy * u_cell / u_viewport * 2.0 - 1.0;
  float w;
  vec3 D = domePoint(ndc, w);
  o_mottle = mottleAt(D, w);
}
