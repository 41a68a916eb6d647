#version 450 core
// Ink diffusion, boundary iteration, step 1 of 3: each receiver p asks every 8-neighbour i
// for capacity_p · excess_i / Σ excess, excess = max(0, I − I_r); demand_p holds
// capacity_p / Σ excess (0 when no neighbour has ink above the residual, or p is a
// stroke pixel). Pixels outside the image are absent.
layout(local_size_x = 16, local_size_y = 16) in;
layout(r32f, binding = 0) readonly uniform image2D u_ink;
layout(r32f, binding = 1) readonly uniform image2D u_original;  // ink before diffusion: the strokes
layout(r32f, binding = 2) writeonly uniform image2D u_demand;
layout(binding = 0) uniform sampler2D u_absorbency;             // tiled over the picture
uniform vec2 u_absorbency_map;  // absorbency = clamp(y + x · texel, 0, 1)
uniform float u_capacity;   // I_p / n
uniform float u_residual;
uniform float u_threshold;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(u_ink);
  if (any(greaterThanEqual(p, size))) return;
  float demand = 0.0;
  if (imageLoad(u_original, p).r <= u_threshold) {
    float sum = 0.0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec2 q = p + ivec2(dx, dy);
        if ((dx == 0 && dy == 0) || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
        sum += max(0.0, imageLoad(u_ink, q).r - u_residual);
      }
    float a = clamp(u_absorbency_map.y + u_absorbency_map.x * texelFetch(u_absorbency, p % textureSize(u_absorbency, 0), 0).r,
                    0.0, 1.0);
    if (sum > 0.0) demand = u_capacity * a / sum;
  }
  imageStore(u_demand, p, vec4(demand));
}
