// Slope-following wrinkle (cun) strokes, seed 001 Eq. 5's luma with the texture turned down
// the fall line, shared by the two places that compute it: the G-buffer pass (any UVs, from
// the triangle's screen derivatives) and the ink pass (planar UVs, from the tangent plane of
// the rebuilt position; one evaluation per pixel instead of one per covered fragment).

#include "ink_hash.glsl"

// The wrinkle texture at one octave: q are tile coordinates (one unit per tile), turned by
// m about the three nearest points of a triangular lattice of half-tile spacing (each with
// its own random offset into the texture) and blended with weights that fall smoothly to 0
// away from each point, so a turn that changes across the surface bends the strokes instead
// of sliding the texture from a far origin. (A square lattice needs four reads: on a
// software rasteriser each costs about 1.5 % of a frame.)
float wrinkleOctave(sampler2D tex, vec2 q, mat2 m, float lod) {
  const float F2 = 0.36602540, G2 = 0.21132487;  // the skew and unskew of 2D simplex noise
  vec2 cell = q * 2.0;
  vec2 base = floor(cell + dot(cell, vec2(F2)));  // skewed lattice coordinates of corner 0
  vec2 x0 = cell - base + dot(base, vec2(G2));   // from corner 0, in cells
  vec2 i1 = x0.x > x0.y ? vec2(1.0, 0.0) : vec2(0.0, 1.0);
  float sum = 0.0, total = 0.0;
  for (int i = 0; i < 3; ++i) {
    vec2 step_ = i == 0 ? vec2(0.0) : (i == 1 ? i1 : vec2(1.0));
    vec2 x = x0 - step_ + dot(step_, vec2(G2));  // from this corner, in cells
    uint h = cellHash(uvec2(ivec2(base + step_) + 32768));
    vec2 offset = vec2(h & 0xffffu, h >> 16) / 65536.0;
    float r = max(0.5 - dot(x, x), 0.0);
    float weight = r * r;
    vec2 t = m * (x * 0.5) + offset;  // x / 2: from the corner in tile units
    sum += weight * textureLod(tex, t, lod).r;
    total += weight;
  }
  return sum / total;
}

// Eq. 5's luma at UV `uv` of a surface of unit normal n (world, +Z up), with the texture's v
// axis down the fall line: the fall line (the steepest descent on the surface) is carried
// into UV space through the position's and the UVs' screen derivatives (dpx, dpy: world
// units per pixel; dux, duy: UV units per pixel), and the tile's size on screen is held near
// `tile_px` by blending the two power-of-two octaves around it (from half to twice it, the
// nearer weighing more), so the strokes keep their size as the camera zooms and stay on the
// surface as it moves. `angle` (radians) turns the strokes from the fall line. Where the UVs
// do not change across the screen the texture's mean (its coarsest level) stands in.
float slopeWrinkle(sampler2D tex, vec3 n, vec2 uv, vec3 dpx, vec3 dpy, vec2 dux, vec2 duy, float tile_px,
                   float angle) {
  float det = dux.x * duy.y - duy.x * dux.y;
  if (!(abs(det) > 1e-30)) return textureLod(tex, uv, 1000.0).r;
  vec3 tu = (dpx * duy.y - dpy * dux.y) / det;  // dP/du
  vec3 tv = (dpy * dux.x - dpx * duy.x) / det;  // dP/dv
  vec3 down = vec3(0.0, 0.0, -1.0) + n.z * n;   // -Z less its normal part
  float uu = dot(tu, tu), uv_ = dot(tu, tv), vv = dot(tv, tv);
  float gram = uu * vv - uv_ * uv_;
  vec2 d = gram > 0.0 ? vec2(vv * dot(down, tu) - uv_ * dot(down, tv), uu * dot(down, tv) - uv_ * dot(down, tu)) / gram
                      : vec2(0.0);
  // On flat ground there is no fall line: the strokes run along v there.
  float steep = smoothstep(0.02, 0.15, length(down));
  vec2 dir = length(d) > 0.0 ? normalize(d) : vec2(0.0, 1.0);
  dir = mix(vec2(0.0, 1.0), dir, steep);
  dir = length(dir) > 1e-6 ? normalize(dir) : vec2(0.0, 1.0);
  float c = cos(angle), s = sin(angle);
  dir = vec2(c * dir.x - s * dir.y, s * dir.x + c * dir.y);
  mat2 m = mat2(dir.y, dir.x, -dir.x, dir.y);  // takes dir to (0, 1): rows (dir.y, -dir.x), (dir.x, dir.y)
  float scale = log2(max(tile_px * sqrt(abs(det)), 1e-30));  // log2 of tiles' UV size at tile_px
  float level = floor(scale), blend = scale - level;
  float size0 = exp2(level), size1 = 2.0 * size0;
  // One mip level per octave, from the footprint of a pixel in texels (turning does not
  // change it): explicit-gradient fetches cost llvmpipe a level computation each.
  float texels = float(textureSize(tex, 0).x) * max(length(dux), length(duy));
  float lod0 = log2(max(texels / size0, 1e-30));
  float a = wrinkleOctave(tex, uv / size0, m, lod0);
  float b = wrinkleOctave(tex, uv / size1, m, lod0 - 1.0);
  return mix(a, b, blend);
}
