#version 450 core
// Ink diffusion, boundary iteration, step 2 of 3: a donor gives at most its excess, so its
// neighbours' requests are scaled down together; transfer i→p = demand_p · supply_i.
layout(local_size_x = 16, local_size_y = 16) in;
layout(r32f, binding = 0) readonly uniform image2D u_ink;
layout(r32f, binding = 2) readonly uniform image2D u_demand;
layout(r32f, binding = 3) writeonly uniform image2D u_supply;
uniform float u_residual;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_ink);
  if (any(greaterThanEqual(p, size))) return;
  float asked = 0.0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      ivec2 q = p + ivec2(dx, dy);
      if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
      asked += imageLoad(u_demand, q).r;
    }
  float excess = max(0.0, imageLoad(u_ink, p).r - u_residual);
  // Scaled a hair under the exact share so float rounding cannot overdraw the donor.
  float supply = excess * asked > excess ? excess / asked * (1.0 - 4e-7) : excess;
  imageStore(u_supply, p, vec4(supply));
}
