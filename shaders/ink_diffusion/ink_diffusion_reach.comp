#version 450 core
// Ink diffusion: which areas of the picture lie within u_reach pixels (Chebyshev, so also
// city-block) of a block marked by the extraction. Used twice: the boundary iterations'
// work groups (ink moves at most one pixel per iteration, so after n iterations only
// pixels within n of ink above the residual — within n + d of a marked block, counting
// the rings — can change) and the main region's blocks (rings lie within d of a stroke).
// One invocation per area of u_area pixels; marks are per block of BLOCK_SIZE² pixels.
layout(local_size_x = 8, local_size_y = 8) in;
layout(r8ui, binding = 0) readonly uniform uimage2D u_marks;
layout(r8ui, binding = 1) writeonly uniform uimage2D u_reached;
uniform ivec2 u_area;
uniform int u_reach;
uniform ivec2 u_lo, u_hi;  // the window computed, in texels of u_reached (marks outside it are read too)

void main() {
  ivec2 g = u_lo + ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, u_hi))) return;
  ivec2 lo = max(g * u_area - u_reach, ivec2(0)) / BLOCK_SIZE;
  ivec2 hi = min((g * u_area + u_area - 1 + u_reach) / BLOCK_SIZE, imageSize(u_marks) - 1);
  uint reached = 0u;
  for (int y = lo.y; y <= hi.y && reached == 0u; ++y)
    for (int x = lo.x; x <= hi.x && reached == 0u; ++x) reached = imageLoad(u_marks, ivec2(x, y)).r;
  imageStore(u_reached, g, uvec4(reached));
}
