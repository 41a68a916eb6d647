// What a per-pixel shader that may run as a compute shader (pixel_main.glsl) needs before its
// own code: the work group, the rectangle of pixels a dispatch covers, the depth the compute
// stage tests itself, and PIXEL_COORD, the pixel's centre in window coordinates.
#ifdef PIXEL_COMPUTE
layout(local_size_x = 8, local_size_y = 8) in;
uniform ivec4 u_pixel_rect;  // x0, y0, x1, y1 (exclusive): the pixels of the dispatch
#if defined(PIXEL_SURFACES) || defined(PIXEL_BACKGROUND)
layout(binding = 7) uniform sampler2D u_pixel_depth;  // the G-buffer's
#endif
#define PIXEL_COORD (vec2(ivec2(gl_GlobalInvocationID.xy) + u_pixel_rect.xy) + 0.5)
#else
#define PIXEL_COORD gl_FragCoord.xy
#endif
