// Water (scene key `water`), for the ink pass: below the level the land is hidden and the
// water is left as paper with sparse horizontal wave strokes, anchored on the water's
// surface in the world (they move with the scene, not with the screen); where land meets
// the water, a bank line. Needs ink_surface.glsl (u_depth, the camera, worldPosition).
#include "ink_hash.glsl"

// The water's level, waves, bank and extent come in the frame's block (frame_params.glsl).

// Where this pixel's view ray meets the water's surface: the point w, the ray's parameter t
// and unit direction d; false when it does not (looking up or along the surface).
bool waterHit(ivec2 p, out vec3 w, out float t, out vec3 d) {
  vec2 ndc = (vec2(p) + 0.5) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
  vec4 a = u_inverse_view_projection * vec4(ndc, -1.0, 1.0), b = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
  vec3 o = a.xyz / a.w;
  d = normalize(b.xyz / b.w - o);
  t = (u_water.x - o.z) / (abs(d.z) > 1e-6 ? d.z : -1e-6);
  w = o + t * d;
  return t > 0.0;
}

bool underWater(vec3 position) {
  return position.z < u_water.x;
}

// The wave strokes' ink at w, where a view ray of direction d meets the water at parameter
// t (waterHit), in [0, 1], times `share` (what the atmosphere leaves of it; 0: none, and no
// cell is looked at: a software rasteriser runs a branch for its whole group of pixels, but
// leaves a loop once none of them has a turn left).
float waveInkAt(vec3 w, float t, vec3 d, float share) {
  if (u_water.z <= 0.0) return 0.0;
  // A pixel on the water, in cells: across (u) as it is, along the view foreshortened.
  float pixel = t * u_pixel_angle / u_water.y, graze = max(abs(d.z), 0.02);
  float cell_px = graze / pixel;  // a cell's height on the picture, pixels
  float visible = smoothstep(2.0, 6.0, cell_px);  // far water goes bare before it turns to grey
  if (visible <= 0.0) return 0.0;
  vec2 away = vec2(-u_water_right.y, u_water_right.x);
  vec2 q = vec2(dot(w.xy, u_water_right), dot(w.xy, away)) / u_water.y;
  float half_thick = 0.5 * max(0.9 * u_water_bank, 1.6) * pixel / graze;  // cells along `away`
  ivec2 c = ivec2(floor(q));
  float ink = 0.0;
  // A stroke lies in its cell's middle band and may reach into the cells beside it.
  int last = share > 0.0 && visible > 0.0 ? 1 : -2;
  for (int dx = -1; dx <= last; ++dx) {
    uvec2 cell = uvec2(c + ivec2(dx, 0) + 32768);
    uint h = cellHash(cell);
    if (float(h & 0xffffu) / 65535.0 >= u_water.z) continue;
    uint g = cellHash(cell ^ uvec2(0x9e3779b9u, 0x7f4a7c15u));
    float centre_u = float(c.x + dx) + 0.5 + 0.4 * (float(g & 0xffu) / 255.0 - 0.5);
    float centre_v = float(c.y) + 0.25 + 0.5 * float((g >> 8) & 0xffu) / 255.0;
    float half_len = 0.35 + 0.45 * float((g >> 16) & 0xffu) / 255.0;
    float s = (q.x - centre_u) / half_len;
    if (abs(s) >= 1.0) continue;
    // A shallow wave along the stroke, thickest in its middle, fading at its ends.
    float bend = ((g >> 24) & 1u) == 0u ? 1.0 : -1.0;
    float v = centre_v + bend * 0.08 * sin(3.14159265 * s);
    float thick = half_thick * (1.0 - 0.6 * s * s);
    // Coverage of this pixel by the stroke, in pixels across it (cell_px to a cell): a line
    // under two pixels thick stays one line instead of breaking into the dashes a test of
    // the pixel's centre alone leaves where it bends across rows.
    float cover = clamp((thick - abs(q.y - v)) * cell_px + 0.5, 0.0, 1.0);
    ink = max(ink, cover * (1.0 - smoothstep(0.75, 1.0, abs(s))));
  }
  return share * (ink * visible * u_water.w);
}

// The wave strokes' ink where this pixel's view ray meets the water, in [0, 1], times share.
float waveInk(ivec2 p, float share) {
  vec3 w, d;
  float t;
  return waterHit(p, w, t, d) ? waveInkAt(w, t, d, share) : 0.0;
}

// Open water where no land was drawn (between ranges, in front of a near bank): the wave
// strokes where the view ray meets the water inside the land's rectangle, fading out over
// its outer fifth as a dissolving border does, with the distance fade and the mist at the
// water's height. Needs presence's uniforms (ink_surface.glsl).
float openWaterInk(ivec2 p) {
  vec3 w, d;
  float t;
  if (!waterHit(p, w, t, d)) return 0.0;
  vec2 size = u_water_extent.zw - u_water_extent.xy;
  vec2 inside = min(w.xy - u_water_extent.xy, u_water_extent.zw - w.xy) / max(0.2 * min(size.x, size.y), 1e-6);
  float f = smoothstep(0.0, 1.0, min(inside.x, inside.y));
  if (f <= 0.0) return 0.0;
  f *= 1.0 - u_fade * smoothstep(u_fade_range.x, u_fade_range.y, distance(u_eye, w));
#ifdef MIST
  f *= 1.0 - mistAt(w);
#endif
  return waveInkAt(w, t, d, f);
}

// The bank line's ink at world xy along the shore: 1, an even line; with u_water_bank_break,
// value noise over cells of half a wave cell leaves gaps where it is low (below 0.33: a
// quarter of the shore, fading in up to 0.43) and varies the ink of what stays, as a brush
// drawn along a shore lifts and presses.
float bankInk(vec2 xy) {
  vec2 q = xy / max(0.5 * u_water.y, 1e-6), f = fract(q);
  uvec2 c = uvec2(ivec2(floor(q)) + 32768);
  float n = cellValue(c, f * f * (3.0 - 2.0 * f), 0u);
  return mix(1.0, smoothstep(0.33, 0.43, n) * (0.6 + 0.4 * n), u_water_bank_break);
}

// On the land's side of a bank (a neighbour within the line's width is under water) the
// line's ink there (bankInk), elsewhere 0. position is the pixel's point (world) and
// z_per_pixel how much its height changes to a neighbour (a 2 × 2 quad's screen
// derivative): a pixel higher above the water than r such steps (with room for the quad's
// estimate to be low) has no neighbour under it, and reads none.
float bankLine(ivec2 p, vec3 position, float z_per_pixel) {
  if (u_water_bank <= 0.0) return 0.0;
  int r = max(1, int(round(u_water_bank)));
  // Elsewhere a loop of no turns: a software rasteriser runs a branch for its whole group of
  // pixels, but leaves a loop once none of them has a turn left.
  int sides = position.z - u_water.x > 4.0 * float(r) * z_per_pixel + 1e-4 * abs(u_water.x) + 1e-6 ? 0 : 4;
  ivec2 size = textureSize(u_depth, 0);
  for (int k = 0; k < sides; ++k) {
    ivec2 q = p + r * ivec2(k == 0 ? 1 : (k == 1 ? -1 : 0), k == 2 ? 1 : (k == 3 ? -1 : 0));
    if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) continue;
    float depth = texelFetch(u_depth, q, 0).r;
    if (depth < 1.0 && underWater(worldPosition(q, depth))) return bankInk(position.xy);
  }
  return 0.0;
}
