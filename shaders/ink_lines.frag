#version 450 core
// Strokes for the ink pass (its STROKES variant): one pixel wide centre lines where a painter
// would put a stroke, each stamped as a disc of its half-width into u_stroke_ink with an
// atomic max (ink does not add up on one stroke), so the ink pass reads one texel per pixel
// and the cost follows the number of centres, not the area times the reach. Centres are
// - outlines: the near side of a depth jump (occluding contours, the skyline), full ink;
// - crests: pixels past Eq. 1's threshold where the curvature peaks across the line
//   (non-maximum suppression), so a broad band of high curvature gives its crest line and a
//   smooth hill gives no filled disc; concave crests (valleys, crevices) get lighter ink;
// - silhouettes: where N·V is below the threshold and smallest across the line.
// Width tapers with the crest's strength and with distance; the atmosphere (fade, mist,
// border) is applied here, at the centre, so a stroke overrunning onto the paper keeps it.
#include "ink_objects.glsl"
#include "ink_surface.glsl"
// Ink × 255 per pixel, cleared to 0 each frame.
layout(r32ui, binding = 3) uniform uimage2D u_stroke_ink;

vec3 normalAt(ivec2 q) {
  return normalize(imageLoad(u_normal_curvature, q).xyz * 2.0 - 1.0);
}

// |N·V| at q, 1 on the background (whose targets are not cleared).
float facing(ivec2 q, vec3 v) {
  return texelFetch(u_depth, q, 0).r >= 1.0 ? 1.0 : abs(dot(normalAt(q), v));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(u_depth, p, 0).r;
  if (depth >= 1.0) return;
#ifdef SINGLE_OBJECT
  ObjectParams o = objects[0];
#else
  ObjectParams o = objects[int(imageLoad(u_surface_id, p).a * 255.0 + 0.5) - 1];
#endif
  if ((o.line_flags & kStrokes) == 0u) return;
  vec3 position = worldPosition(p, depth);
  vec4 nc = imageLoad(u_normal_curvature, p);
  float ink = 0.0, strength = 0.0;

  float jump = o.depth_edges;
  if (jump > 0.0) {
    float z = viewDepth(depth);
    if (viewDepth(farthestNeighbour(p)) - z > jump * z) ink = strength = 1.0;
  }

  if (ink < 1.0 && (o.line_flags & kNormalOnly) == 0u) {
    // Eq. 1's weight, then the crest test across the line.
    float col = 1.0 - decodeCurvature(nc.w) * o.curve_factor;
    float threshold = o.line_threshold, soft = o.soft_width;
    float weight = soft > 0.0 ? 1.0 - smoothstep(threshold - 0.5 * soft, threshold + 0.5 * soft, col)
                              : (col < threshold ? 1.0 : 0.0);
    if (weight > 0.0) {
      float l = curvatureCode(p - ivec2(1, 0)), r = curvatureCode(p + ivec2(1, 0));
      float d = curvatureCode(p - ivec2(0, 1)), u = curvatureCode(p + ivec2(0, 1));
      // A crest is a maximum across the line; along it the curvature may rise or fall, so
      // the axis is the one where the field bends down most (its gradient vanishes on the
      // crest and cannot tell).
      bool across_x = l + r <= d + u;
      if (across_x ? nc.w >= max(l, r) : nc.w >= max(d, u)) {
        // Convex or concave across the line: normals spread apart over a ridge
        // ((n₊ − n₋)·(x₊ − x₋) > 0) and come together in a valley.
        ivec2 a = across_x ? ivec2(1, 0) : ivec2(0, 1);
        float d_plus = texelFetch(u_depth, p + a, 0).r, d_minus = texelFetch(u_depth, p - a, 0).r;
        float valley = 1.0;
        if (d_plus < 1.0 && d_minus < 1.0) {
          vec3 dn = normalAt(p + a) - normalAt(p - a);
          vec3 dx = worldPosition(p + a, d_plus) - worldPosition(p - a, d_minus);
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
    float nv = abs(dot(normalize(nc.xyz * 2.0 - 1.0), v));
    if (nv < 0.5 * silhouette) {
      float l = facing(p - ivec2(1, 0), v), r = facing(p + ivec2(1, 0), v);
      float d = facing(p - ivec2(0, 1), v), u = facing(p + ivec2(0, 1), v);
      bool trough = l + r >= d + u ? nv <= min(l, r) : nv <= min(d, u);
      if (trough) ink = strength = 1.0;
    }
  }

  if (ink <= 0.0) return;
  float far = smoothstep(u_fade_range.x, u_fade_range.y, distance(u_eye, position));
  float half_width = o.stroke_half_width * mix(o.stroke_taper, 1.0, strength) * mix(1.0, o.stroke_far, far);
  ink *= presence(o, position);
  // The disc, its edge antialiased over one pixel; stamps outside the image are dropped.
  float reach = half_width + 0.5;
  int r = int(ceil(reach));
  for (int dy = -r; dy <= r; ++dy) {
    for (int dx = -r; dx <= r; ++dx) {
      float cover = clamp(reach - length(vec2(dx, dy)), 0.0, 1.0);
      uint v = uint(ink * cover * 255.0 + 0.5);
      if (v > 0u) imageAtomicMax(u_stroke_ink, p + ivec2(dx, dy), v);
    }
  }
}
