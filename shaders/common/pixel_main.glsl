// The `main` of a per-pixel shader that runs either as a fragment shader over a full-screen
// triangle (fullscreen.vert, depth-tested against a copy of the G-buffer's depth) or, with
// PIXEL_COMPUTE, as a compute shader of 8x8 groups over the same pixels (issue 47: on GPUs
// whose graphics pipeline runs on a few of their multiprocessors, such as the H100's two
// graphics TPCs of 66, a full-screen fragment pass uses a small part of the chip, compute
// all of it). Included at the end of the shader, after its `shadePixel()`, which reads
// PIXEL_COORD instead of gl_FragCoord.xy. With PIXEL_COMPUTE the shader defines
// `pixelOutputsClear()` (its outputs become plain variables, zero before each pixel) and
// `pixelStore(ivec2)` (their image stores); the depth test the fragment stage gets from the
// depth buffer is PIXEL_SURFACES (the G-buffer's depth below 1: a surface) or
// PIXEL_BACKGROUND (at 1: nothing drawn there), read from u_pixel_depth.
#ifdef PIXEL_COMPUTE
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy) + u_pixel_rect.xy;
  if (p.x >= u_pixel_rect.z || p.y >= u_pixel_rect.w) return;
#if defined(PIXEL_SURFACES) || defined(PIXEL_BACKGROUND)
  float pixel_depth = texelFetch(u_pixel_depth, p, 0).r;
#ifdef PIXEL_SURFACES
  if (pixel_depth >= 1.0) return;
#else
  if (pixel_depth < 1.0) return;
#endif
#endif
  pixelOutputsClear();
  shadePixel();
  pixelStore(p);
}
#else
void main() { shadePixel(); }
#endif
