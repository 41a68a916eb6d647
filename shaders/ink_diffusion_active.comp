#version 450 core
// Ink diffusion: which work groups of the boundary iterations can see any change. Ink
// moves at most one pixel per iteration, so after n iterations only pixels within n of a
// pixel with ink above the residual at the start can differ; those lie within d of a
// block of SEED_SIZE² pixels marked by the extraction (u_seeds). One invocation per work
// group's area of AREA_W × AREA_H pixels.
layout(local_size_x = 8, local_size_y = 8) in;
layout(r8ui, binding = 0) readonly uniform uimage2D u_seeds;
layout(r8ui, binding = 1) writeonly uniform uimage2D u_active;
uniform int u_reach;  // n + d, in pixels

void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(g, imageSize(u_active)))) return;
  const ivec2 area = ivec2(AREA_W, AREA_H);
  ivec2 lo = max(g * area - u_reach, ivec2(0)) / SEED_SIZE;
  ivec2 hi = min((g * area + area - 1 + u_reach) / SEED_SIZE, imageSize(u_seeds) - 1);
  uint reached = 0u;
  for (int y = lo.y; y <= hi.y && reached == 0u; ++y)
    for (int x = lo.x; x <= hi.x && reached == 0u; ++x) reached = imageLoad(u_seeds, ivec2(x, y)).r;
  imageStore(u_active, g, uvec4(reached));
}
