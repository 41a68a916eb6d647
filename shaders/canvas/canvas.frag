#version 450 core
// Dynamic canvas: one noise kernel per quad, added into a float target (blending ONE, ONE),
// scaled by 1 / σ so the paper has unit variance.
#include "noise_gabor.glsl"
#ifndef CANVAS_SILK
#include "noise_perlin.glsl"
#endif
#include "canvas_kernel.glsl"

in vec2 g_offset;
flat in vec4 g_impulse;
layout(location = 0) out vec2 o_canvas;  // grain; no marks (blended additively)

void main() { o_canvas = vec2(g_impulse.x * canvasKernel(g_offset, g_impulse.yzw) * u_kernel_misc.w, 0.0); }
