#version 450 core
// Ink diffusion, one boundary iteration in one dispatch: the three order-independent
// gathers of libs/ink (demand, capped supply, transfer) fused, each invocation recomputing
// the demands and supplies its pixels need instead of storing them between passes.
//
// The ink and the capacity are packed two pixels to a texel (pixel x in channel x & 1 of
// texel x / 2; see InkDiffusionPass). Each invocation owns BLOCK adjacent columns (BLOCK / 2
// texels) and walks STRIP_ROWS rows down them, in work groups of GROUP_INVOCATIONS
// (compile-time constants from the pass), carrying the rows it needs in registers: reading
// ink row r gives the demand of row r − 1 (excess of rows r − 2 … r), the supply of row
// r − 2 (demands of rows r − 3 … r − 1) and the new ink of row r − 3 (supplies of rows
// r − 4 … r − 2). A pixel's demand and supply are computed by every invocation that needs
// them, from the same values in the same order, so donor and receiver agree on every
// transfer and ink is conserved up to float rounding. One dispatch and (BLOCK + 6) / BLOCK
// texel reads per pixel replace three dispatches and 20 reads: on llvmpipe a pass costs
// mostly its invocations and image accesses, not its arithmetic, and a two-channel load
// costs what a one-channel one does.
//
// Loads outside the image return 0 and stores there are dropped (OpenGL 4.5, section
// 8.26): outside pixels have no excess and no capacity, so they neither give nor take.
// The unused half of the last texel of an odd width holds 0 in both images, so it is
// outside in the same sense, and it stays 0.
//
// A work group whose area no ink above the residual can reach in this frame's iterations
// (u_active = 0) leaves its pixels as they are; the pass copies the start into both
// ping-pong images, so they already hold those pixels.
layout(local_size_x = GROUP_INVOCATIONS) in;
layout(rg32f, binding = 0) readonly uniform image2D u_ink;
layout(rg32f, binding = 1) readonly uniform image2D u_capacity;  // I_p / n · absorbency; 0 on strokes
layout(rg32f, binding = 2) writeonly uniform image2D u_next;
layout(r8ui, binding = 3) readonly uniform uimage2D u_active;  // one texel per work group
uniform float u_residual;
uniform ivec2 u_areas_lo;  // the window's first work-group area (the dispatch covers its areas)

const int B = BLOCK, T = BLOCK / 2;  // columns and texels an invocation owns

// Σ over the 8 neighbours of column c + 1 of three rows; the same order for every caller.
#define NEIGHBOURS(a, b, c, k) (a[k] + a[k + 1] + a[k + 2] + b[k] + b[k + 2] + c[k] + c[k + 1] + c[k + 2])

void main() {
  const ivec2 area = u_areas_lo + ivec2(gl_WorkGroupID.xy);
  if (imageLoad(u_active, area).r == 0u) return;
  ivec2 size = imageSize(u_ink);  // in texels
  int t0 = (area.x * GROUP_INVOCATIONS + int(gl_LocalInvocationID.x)) * T;  // first texel owned; columns x0 = 2 · t0 …
  int y0 = area.y * STRIP_ROWS;
  if (t0 >= size.x) return;
  float e0[B + 6], e1[B + 6], e2[B + 6];   // excess, columns x0 − 3 …, rows r − 2, r − 1, r
  float d0[B + 4], d1[B + 4], d2[B + 4];   // demand, columns x0 − 2 …, rows r − 3 … r − 1
  float s0[B + 2], s1[B + 2], s2[B + 2];   // supply, columns x0 − 1 …, rows r − 4 … r − 2
  float l0[B], l1[B];                      // loss (all a donor sends), columns x0 …, rows r − 3, r − 2
  float i0[B], i1[B], i2[B], i3[B];        // ink, columns x0 …, rows r − 3 … r
  for (int c = 0; c < B + 6; ++c) e1[c] = e2[c] = 0.0;
  for (int c = 0; c < B + 4; ++c) d1[c] = d2[c] = 0.0;
  for (int c = 0; c < B + 2; ++c) s1[c] = s2[c] = 0.0;
  for (int c = 0; c < B; ++c) l1[c] = i1[c] = i2[c] = i3[c] = 0.0;
  const int last = min(y0 + STRIP_ROWS, size.y) + 2;  // row r that gives the strip's last row
  for (int r = y0 - 3; r <= last; ++r) {
    e0 = e1;
    e1 = e2;
    i0 = i1;
    i1 = i2;
    i2 = i3;
    float row[B + 8];  // ink, columns x0 − 4 … x0 + B + 3 (texels t0 − 2 … t0 + T + 1)
    for (int t = 0; t < T + 4; ++t) {
      vec2 pair = imageLoad(u_ink, ivec2(t0 - 2 + t, r)).rg;
      row[2 * t] = pair.r;
      row[2 * t + 1] = pair.g;
    }
    for (int c = 0; c < B + 6; ++c) e2[c] = max(0.0, row[c + 1] - u_residual);
    for (int c = 0; c < B; ++c) i3[c] = row[c + 4];
    // Demand of row r − 1: capacity / Σ excess of the neighbours (0 without excess).
    d0 = d1;
    d1 = d2;
    float capacity[B + 4];  // columns x0 − 2 … x0 + B + 1 (texels t0 − 1 … t0 + T)
    for (int t = 0; t < T + 2; ++t) {
      vec2 pair = imageLoad(u_capacity, ivec2(t0 - 1 + t, r - 1)).rg;
      capacity[2 * t] = pair.r;
      capacity[2 * t + 1] = pair.g;
    }
    for (int c = 0; c < B + 4; ++c) {
      float sum = NEIGHBOURS(e0, e1, e2, c);
      d2[c] = sum > 0.0 ? capacity[c] / sum : 0.0;
    }
    // Supply of row r − 2: the excess, scaled down together if the neighbours ask for more
    // (a hair under the exact share, so float rounding cannot overdraw the donor).
    s0 = s1;
    s1 = s2;
    l0 = l1;
    for (int c = 0; c < B + 2; ++c) {
      float asked = NEIGHBOURS(d0, d1, d2, c);
      float excess = e0[c + 2];
      float supply = excess * asked > excess ? excess / asked * (1.0 - 4e-7) : excess;
      s2[c] = supply;
      if (c >= 1 && c < B + 1) l1[c - 1] = supply * asked;
    }
    // New ink of row r − 3: what it receives less what it sends.
    int y = r - 3;
    if (y < y0) continue;
    float next[B];
    for (int c = 0; c < B; ++c) next[c] = max(i0[c] + d0[c + 2] * NEIGHBOURS(s0, s1, s2, c) - l0[c], 0.0);
    for (int t = 0; t < T; ++t) imageStore(u_next, ivec2(t0 + t, y), vec4(next[2 * t], next[2 * t + 1], 0.0, 0.0));
  }
}
