#version 450 core
// Ink diffusion, boundary iteration, step 3 of 3: every pixel gains what its neighbours
// send it and loses what it sends them (the same products on both sides, so ink is
// conserved up to float rounding).
layout(local_size_x = 16, local_size_y = 16) in;
layout(r32f, binding = 0) readonly uniform image2D u_ink;
layout(r32f, binding = 2) readonly uniform image2D u_demand;
layout(r32f, binding = 3) readonly uniform image2D u_supply;
layout(r32f, binding = 4) writeonly uniform image2D u_next;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_ink);
  if (any(greaterThanEqual(p, size))) return;
  float demand_sum = 0.0, supply_sum = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = p + ivec2(dx, dy);
      if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      demand_sum += imageLoad(u_demand, q).r;
      supply_sum += imageLoad(u_supply, q).r;
    }
  float ink = imageLoad(u_ink, p).r;
  float next = ink + imageLoad(u_demand, p).r * supply_sum - imageLoad(u_supply, p).r * demand_sum;
  imageStore(u_next, p, vec4(max(next, 0.0)));
}
