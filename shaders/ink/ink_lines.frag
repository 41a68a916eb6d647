#version 450 core
// Strokes for the ink pass (its STROKES variant): one pixel wide centre lines where a painter
// would put a stroke, each stamped as a disc of its half-width into u_stroke_ink with an
// atomic max (ink does not add up on one stroke), so the ink pass reads one texel per pixel
// and the cost follows the number of centres, not the area times the reach. Centres are
// - outlines: the near side of a depth jump (occluding contours, the skyline), full ink;
// - crests: pixels past Eq. 1's threshold where the curvature peaks across the line
//   (non-maximum suppression), so a broad band of high curvature gives its crest line and a
//   smooth hill gives no filled disc; concave crests (valleys, crevices) get lighter ink;
// - silhouettes: where N·V is below the threshold and smallest across the line;
// - suggestive contours (SUGGESTIVE; DeCarlo et al. 2003): where N·V has a local minimum
//   along w, the view direction projected into the tangent plane (equivalently, the radial
//   curvature crosses zero with D_w κ_r > 0): the contours the surface would show from a
//   slightly different view, lighter ink.
// Width tapers with the crest's strength and with distance; the atmosphere (fade, mist,
// border) is applied here, at the centre, so a stroke overrunning onto the paper keeps it.
// With PIXEL_COMPUTE it is a compute shader (pixel_main.glsl) that tests the depth itself.
#include "pixel_stage.glsl"
#include "ink_objects.glsl"
#include "ink_surface.glsl"
#include "ink_hash.glsl"
#ifdef STROKE_GATHER
// Each centre's ink and reach (half-width + half a pixel), cleared to 0 each frame; ink.frag
// gathers them. Compute only: a centre is a pixel output, stored by pixelStore.
#ifndef PIXEL_COMPUTE
#error STROKE_GATHER needs PIXEL_COMPUTE
#endif
layout(rg32f, binding = 3) writeonly uniform image2D u_stroke_centre;
#else
// Ink × 255 per pixel, cleared to 0 each frame.
layout(r32ui, binding = 3) uniform uimage2D u_stroke_ink;
#endif
// What the ink pass would otherwise compute again at each surface pixel: what the atmosphere
// and the border leave (presence(), r; for land under water, at the water's surface above
// it) and the shading's noise (surfaceNoise(): erosion g, added noise b).
#ifdef PIXEL_COMPUTE
layout(rgba16, binding = 7) writeonly uniform image2D u_presence_noise_out;
vec4 o_presence_noise;
#ifdef STROKE_GATHER
vec2 o_centre;  // ink, reach; 0 where p is no centre
void pixelOutputsClear() {
  o_presence_noise = vec4(0.0);
  o_centre = vec2(0.0);
}
void pixelStore(ivec2 p) {
  imageStore(u_presence_noise_out, p, o_presence_noise);
  imageStore(u_stroke_centre, p, vec4(o_centre, 0.0, 0.0));
}
#else
void pixelOutputsClear() { o_presence_noise = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(u_presence_noise_out, p, o_presence_noise); }
#endif
#else
layout(location = 0) out vec4 o_presence_noise;
#endif

// The G-buffer's encoded normal: a unit vector to 16 bits a component, so its length is 1
// to ~1e-4 and the tests below need no normalize (seven a pixel cost ~0.5 ms at 1024²).
vec3 decodeNormal(vec4 nc) {
  return nc.xyz * 2.0 - 1.0;
}

vec3 normalAt(ivec2 q) {
  return decodeNormal(imageLoad(u_normal_curvature, q));
}

#ifdef SUGGESTIVE
const float kSuggestiveReach = 3.0;  // pixels either side along w where the trough's depth is measured

// N·V at q (−1 where q is background or across a depth jump from `z`: no trough there).
float facingAlong(ivec2 q, vec3 v, float z) {
  float d = texelFetch(u_depth, q, 0).r;
  if (d >= 1.0 || abs(viewDepth(d) - z) > 0.05 * z) return -1.0;
  return dot(normalAt(q), v);
}

// How deep a trough of N·V along w sits at p (0 where p is not its bottom).
float suggestiveTrough(ivec2 p, vec3 position, vec3 n, float z) {
  vec3 v = normalize(u_eye - position);
  float nv = dot(n, v);
  vec3 w = v - nv * n;
  if (nv <= 0.0 || dot(w, w) < 1e-4) return 0.0;  // facing away, or seen head-on (w undefined)
  // w's direction on screen, in pixels.
  vec4 a = u_view_projection * vec4(position, 1.0);
  vec4 b = u_view_projection * vec4(position + normalize(w) * (1e-3 * z), 1.0);
  vec2 s = (b.xy / b.w - a.xy / a.w) * vec2(textureSize(u_depth, 0));
  if (dot(s, s) < 1e-12) return 0.0;
  s = normalize(s);
  // The bottom: no lower than the pixels one step either side along w.
  ivec2 step1 = ivec2(round(s));
  float n1 = facingAlong(p + step1, v, z), n0 = facingAlong(p - step1, v, z);
  if (n1 < 0.0 || n0 < 0.0 || nv > n1 || nv > n0) return 0.0;
  ivec2 reach = ivec2(round(s * kSuggestiveReach));
  float f1 = facingAlong(p + reach, v, z), f0 = facingAlong(p - reach, v, z);
  if (f1 < 0.0 || f0 < 0.0) return 0.0;
  return min(f0, f1) - nv;
}
#endif

// Depth-tested against the G-buffer's depth before shading (the image atomics would
// otherwise put the test after): only surface pixels run, the background is skipped.
#ifndef PIXEL_COMPUTE
layout(early_fragment_tests) in;
#endif

// The brush's pressure at q (world position over the break's cell): value noise in [0, 1),
// smooth and fixed on the land, so a line's gaps stay put as the camera turns about it (the
// cell, sized from the object's distance as the wet strokes' is, rescales with a zoom).
float strokePressure(vec3 q) {
  vec3 f = fract(q);
  uvec3 c = uvec3(ivec3(floor(q)) + 32768);
  f = f * f * (3.0 - 2.0 * f);
  // Two slices of 2-D value noise, salted by their z, blended along z.
  return mix(cellValue(c.xy, f.xy, c.z * 0x27d4eb2du), cellValue(c.xy, f.xy, (c.z + 1u) * 0x27d4eb2du), f.z);
}

void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
  // Every test below reads p's neighbourhood; each texel is read once. The depth of p, its
  // four neighbours and two diagonal ones come from two gathers (a texel fetch costs a
  // software rasteriser several image loads, and it runs every test's code whether or not a
  // pixel takes it), the neighbours' normal and curvature from four image loads.
  vec2 texel = 1.0 / vec2(textureSize(u_depth, 0));
  vec2 centre = (vec2(p) + 0.5) * texel;
  vec4 upper = textureGather(u_depth, centre + 0.5 * texel);  // p+y, p+x+y, p+x, p
  vec4 lower = textureGather(u_depth, centre - 0.5 * texel);  // p−x, p, p−y, p−x−y
  float depth = upper.w;
  if (depth >= 1.0) return;
#ifdef SINGLE_OBJECT
  ObjectParams o = objects[0];
#else
  ObjectParams o = objects[int(imageLoad(u_surface_id, p).a * 255.0 + 0.5) - 1];
#endif
  // p's world position, unprojected so that its neighbours' cost two multiply-adds each:
  // M·(ndc, 2d − 1, 1) is `column` + d·`per_depth`, and a neighbour along x or y adds ±
  // one pixel's step of M's first or second column.
  mat4 m = u_inverse_view_projection;
  vec4 column = m * vec4(centre * 2.0 - 1.0, -1.0, 1.0), per_depth = 2.0 * m[2];
  vec4 h = column + depth * per_depth;
  vec3 position = h.xyz / h.w;
#ifdef WATER
  // Land under the water is hidden: the atmosphere there is the water surface's above it.
  float here = presence(o, vec3(position.xy, max(position.z, u_water.x)));
#else
  float here = presence(o, position);
#endif
  o_presence_noise = vec4(here, surfaceNoise(o, position), 0.0);
  if ((o.line_flags & kStrokes) == 0u) return;
  vec4 nc = imageLoad(u_normal_curvature, p);
  // The neighbours −x, +x, −y, +y: offset, depth, encoded normal and curvature.
  const ivec2 kSide[4] = ivec2[4](ivec2(-1, 0), ivec2(1, 0), ivec2(0, -1), ivec2(0, 1));
  vec4 side_depth = vec4(lower.x, upper.z, lower.z, upper.x);
  vec4 side_nc[4];
  for (int i = 0; i < 4; ++i) side_nc[i] = imageLoad(u_normal_curvature, p + kSide[i]);
  float ink = 0.0, strength = 0.0;

  float jump = o.depth_edges;
  if (jump > 0.0) {
    // In inverse depth (no divisions): the farthest neighbour is more than `jump` × z behind.
    float iz = inverseViewDepth(depth);
    float farthest = max(max(max(upper.x, upper.y), max(upper.z, upper.w)), max(max(lower.x, lower.y), max(lower.z, lower.w)));
    if (inverseViewDepth(farthest) * (1.0 + jump) < iz) {
      ink = strength = 1.0;
    } else {
      // A fold seen from afar: the surface behind is only a little farther, under the
      // jump, but the step is a kink in inverse depth, which is affine across the screen
      // on any plane. p is on the near side when its 1/z stands above the mean of its two
      // neighbours along x or y by a tenth of the jump (the N·V band of such a fold is
      // thinner than a pixel, so the silhouette test would give only dots).
      float kink_x = 2.0 * iz - inverseViewDepth(side_depth[0]) - inverseViewDepth(side_depth[1]);
      float kink_y = 2.0 * iz - inverseViewDepth(side_depth[2]) - inverseViewDepth(side_depth[3]);
      // Weak kinks (shallow folds) light and thin, those near a jump dark and wide.
      float kink = max(kink_x, kink_y) / (0.1 * jump * iz);
      if (kink > 1.0) {
        strength = smoothstep(1.0, 5.0, kink);
        ink = mix(0.5, 1.0, strength);
      }
    }
  }

  if (ink < 1.0 && (o.line_flags & kNormalOnly) == 0u) {
    // Eq. 1's weight, then the crest test across the line.
    float col = 1.0 - decodeCurvature(nc.w) * o.curve_factor;
    float threshold = o.line_threshold, soft = o.soft_width;
    float weight = soft > 0.0 ? 1.0 - smoothstep(threshold - 0.5 * soft, threshold + 0.5 * soft, col)
                              : (col < threshold ? 1.0 : 0.0);
    if (weight > 0.0) {
      // The neighbours' curvature codes, 0 on the background (curvatureCode's rule).
      vec4 code;
      for (int i = 0; i < 4; ++i) code[i] = side_depth[i] >= 1.0 ? 0.0 : side_nc[i].w;
      // A crest is a maximum across the line; along it the curvature may rise or fall, so
      // the axis is the one where the field bends down most (its gradient vanishes on the
      // crest and cannot tell).
      bool across_x = code[0] + code[1] <= code[2] + code[3];
      if (across_x ? nc.w >= max(code[0], code[1]) : nc.w >= max(code[2], code[3])) {
        // Convex or concave across the line: normals spread apart over a ridge
        // ((n₊ − n₋)·(x₊ − x₋) > 0) and come together in a valley.
        // (Chosen by selects: an index that differs between pixels costs a software
        // rasteriser a load per pixel.)
        float d_plus = across_x ? side_depth[1] : side_depth[3], d_minus = across_x ? side_depth[0] : side_depth[2];
        vec4 nc_plus = across_x ? side_nc[1] : side_nc[3], nc_minus = across_x ? side_nc[0] : side_nc[2];
        float valley = 1.0;
        if (d_plus < 1.0 && d_minus < 1.0) {
          vec3 dn = decodeNormal(nc_plus) - decodeNormal(nc_minus);
          vec4 step = across_x ? m[0] * (2.0 * texel.x) : m[1] * (2.0 * texel.y);
          vec4 h_plus = column + d_plus * per_depth + step, h_minus = column + d_minus * per_depth - step;
          vec3 dx = h_plus.xyz / h_plus.w - h_minus.xyz / h_minus.w;
          if (dot(dn, dx) < 0.0) valley = o.valley_ink;
        }
        // Strength: 0 at the threshold's curvature, 1 at twice it. Weak crests (fine
        // roughness) are lighter and thinner, strong ones dark and wide.
        float excess = (1.0 - col) / max(1.0 - threshold, 1e-3);
        float s = smoothstep(1.0, 2.0, excess);
        float crest_ink = weight * valley * mix(0.5, 1.0, s);
        if (crest_ink > ink) {
          ink = crest_ink;
          strength = s;
        }
      }
    }
  }

  float silhouette = o.silhouette;
  if (ink < 1.0 && silhouette > 0.0) {
    vec3 v = normalize(u_eye - position);
    float nv = abs(dot(decodeNormal(nc), v));
    if (nv < 0.5 * silhouette) {
      // |N·V| of the neighbours, 1 on the background (whose targets are not cleared).
      vec4 f;
      for (int i = 0; i < 4; ++i)
        f[i] = side_depth[i] >= 1.0 ? 1.0 : abs(dot(decodeNormal(side_nc[i]), v));
      bool trough = f[0] + f[1] >= f[2] + f[3] ? nv <= min(f[0], f[1]) : nv <= min(f[2], f[3]);
      if (trough) ink = strength = 1.0;
    }
  }

#ifdef SUGGESTIVE
  if (ink < o.valley_ink && o.suggestive > 0.0) {
    float trough = suggestiveTrough(p, position, decodeNormal(nc), viewDepth(depth));
    if (trough >= o.suggestive) {
      // Strength 0 at the threshold, 1 at three times it: light and thin, as valleys.
      float s = smoothstep(1.0, 3.0, trough / o.suggestive);
      float suggestive_ink = o.valley_ink * mix(0.5, 1.0, s);
      if (suggestive_ink > ink) {
        ink = suggestive_ink;
        strength = 0.5 * s;
      }
    }
  }
#endif

  if (ink <= 0.0) return;
  float far = smoothstep(u_fade_range.x, u_fade_range.y, distance(u_eye, position));
  float half_width = o.stroke_half_width * mix(o.stroke_taper, 1.0, strength) * mix(1.0, o.stroke_far, far);
  ink *= here;
  // A brush lifting and pressing along the line (lines.break): a loop of at most one turn,
  // not a branch, so a software rasteriser skips it for groups of pixels without a centre.
  for (int once = o.line_break > 0.0 ? 0 : 1; once < 1; ++once) {
    // Held within a million cells of the origin, where the cell index stays an integer.
    float pressure = strokePressure(clamp(position / o.line_break_cell, vec3(-1e6), vec3(1e6)));
    // Gaps where the pressure is below 0.36 × break (at 1 about a fifth of the line: the
    // noise's 20th percentile is 0.33), the ink of what stays between 0.55 and 1.
    float lift = 0.36 * o.line_break;
    ink *= smoothstep(lift - 0.04, lift + 0.04, pressure) * mix(1.0, 0.55 + 0.45 * pressure, o.line_break);
    half_width *= mix(1.0, 0.6 + 0.7 * pressure, o.line_break);
  }
  // The disc, its edge antialiased over one pixel; stamps outside the image are dropped.
  // Only the pixels nearer than `reach` are visited, row by row (a software rasteriser
  // pays for every iteration of the square around it: 49 instead of 21 at 3.5 px wide).
  float reach = half_width + 0.5;
#ifdef STROKE_GATHER
  o_centre = vec2(ink, reach);  // the pixels around gather it (ink.frag's strokeInk)
#else
  int r = int(reach);
  for (int dy = -r; dy <= r; ++dy) {
    int w = int(sqrt(reach * reach - float(dy * dy)));
    for (int dx = -w; dx <= w; ++dx) {
      float cover = clamp(reach - length(vec2(dx, dy)), 0.0, 1.0);
      uint v = uint(ink * cover * 255.0 + 0.5);
      if (v > 0u) imageAtomicMax(u_stroke_ink, p + ivec2(dx, dy), v);
    }
  }
#endif
}
#include "pixel_main.glsl"
