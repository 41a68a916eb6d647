// What the image passes over the G-buffer share (ink.frag, ink_lines.frag): the G-buffer's
// targets, positions rebuilt from depth, and how much of a surface point the atmosphere
// (distance fade, mist) and the dissolving border leave standing. Include after
// ink_objects.glsl.
#if defined(BORDER) || defined(MIST)
layout(r8, binding = 5) readonly uniform image2D u_value_noise;
#include "border_noise.glsl"
#endif

#ifdef SHADING
layout(binding = 3) uniform sampler2D u_surface_noise;
#endif

// The shading noise's coordinates at a world position: the object's model x and y.
vec2 noiseCoordinates(ObjectParams o, vec3 position) {
  vec4 w = vec4(position, 1.0);
  return vec2(dot(o.world_to_model_x, w), dot(o.world_to_model_y, w)) * o.noise_frequency;
}

vec3 worldPositionAt(ivec2 p);  // below

// The shading's noise (render_pass.h's erosionNoiseTexture: erosion in r, added noise in g)
// on the object's model x and y, as the G-buffer pass once sampled it per fragment; without
// SHADING no erosion and nothing added. Call it where the control flow is uniform: the
// level of detail comes from the pixel quad's derivatives of the coordinates (across a
// silhouette they are large, and the noise there its coarse average, for a pixel).
vec2 surfaceNoise(ObjectParams o, vec3 position) {
#ifdef SHADING
  vec2 uv = noiseCoordinates(o, position);
#ifdef PIXEL_COMPUTE
  // A compute shader has no derivatives: the coordinates' differences across the pixel's
  // 2x2 quad, from its first pixel, as a fragment shader's level of detail takes them.
  ivec2 q = ivec2(PIXEL_COORD) & ~1;
  vec2 uv00 = noiseCoordinates(o, worldPositionAt(q));
  vec2 dx = noiseCoordinates(o, worldPositionAt(q + ivec2(1, 0))) - uv00;
  vec2 dy = noiseCoordinates(o, worldPositionAt(q + ivec2(0, 1))) - uv00;
  return textureGrad(u_surface_noise, uv, dx, dy).rg;
#else
  return texture(u_surface_noise, uv).rg;
#endif
#else
  return vec2(1.0, 0.5);
#endif
}

// The G-buffer's colour targets are read as images: llvmpipe's image load is about a third
// of the cost of a texel fetch (the ink pass ~10 % cheaper, measured side by side). The
// depth buffer cannot be an image and stays a texture.
layout(rgba16, binding = 0) readonly uniform image2D u_normal_curvature;  // encoded: see ink_gbuffer.frag
layout(rgba8, binding = 1) readonly uniform image2D u_surface_id;
layout(binding = 2) uniform sampler2D u_depth;
// The camera, the distance fade and the mist: the frame's block.
#include "frame.glsl"

vec3 worldPosition(ivec2 p, float depth) {
  vec2 ndc = (vec2(p) + 0.5) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
  vec4 w = u_inverse_view_projection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  return w.xyz / w.w;
}

// The world position pixel p shows (the far plane's point where nothing was drawn).
vec3 worldPositionAt(ivec2 p) { return worldPosition(p, texelFetch(u_depth, p, 0).r); }

// Distance along the view axis from a depth-buffer value; background is infinitely far.
float viewDepth(float d) {
  if (d >= 1.0) return 3.0e38;
  float n = u_near_far.x, f = u_near_far.y;
  return n * f / (f - d * (f - n));
}

// 1 / viewDepth(d), affine in the depth-buffer value: no division by the pixel's depth
// (only by the uniform planes). 0 on the background.
float inverseViewDepth(float d) {
  if (d >= 1.0) return 0.0;
  float n = u_near_far.x, f = u_near_far.y;
  return (1.0 - d) / n + d / f;
}

// The largest depth-buffer value in the 3×3 block around p but its two off corners, from
// two gathers (four texel fetches would cost twice as much on a software rasteriser).
float farthestNeighbour(ivec2 p) {
  vec2 texel = 1.0 / vec2(textureSize(u_depth, 0));
  vec2 centre = (vec2(p) + 0.5) * texel;
  vec4 a = textureGather(u_depth, centre + 0.5 * texel);  // p, p+x, p+y, p+x+y
  vec4 b = textureGather(u_depth, centre - 0.5 * texel);  // p−x−y, p−x, p−y, p
  return max(max(max(a.x, a.y), max(a.z, a.w)), max(max(b.x, b.y), max(b.z, b.w)));
}

// The G-buffer's encoded curvature k / (1 + k) at q (monotone in k), 0 on the background.
float curvatureCode(ivec2 q) {
  if (texelFetch(u_depth, q, 0).r >= 1.0) return 0.0;
  return imageLoad(u_normal_curvature, q).w;
}

// k / (1 + k) back to k; the largest code stands for 65534, not infinity (no 0 · ∞).
float decodeCurvature(float code) {
  return code / (1.0 - min(code, 65534.0 / 65535.0));
}

#ifdef BORDER
// How much of the object is left at `position` (1 inside, 0 at its horizontal border:
// borderLeft), 1 without a border.
float borderPresence(ObjectParams o, vec3 position) {
  if (o.border_width <= 0.0) return 1.0;
  vec4 w = vec4(position, 1.0);
  vec2 m = vec2(dot(o.world_to_model_x, w), dot(o.world_to_model_y, w));
  return borderLeft(m, o.half_extent.xy, o.border_width, o.border_roughness);
}
#endif

#ifdef MIST
// Mist at `position`: full below u_mist.y, thinning over u_mist.z above it, the band broken
// by noise so it lies in banks; u_mist_near of it on the nearest land, all of it on the farthest.
float mistAt(vec3 position) {
  // Noise moves the band by at most u_mist.w: outside that, no noise is needed.
  float h0 = (position.z - u_mist.y) / u_mist.z, reach = u_mist.w / u_mist.z;
  if (h0 >= 1.0 + reach) return 0.0;
  float share = mix(u_mist_near, 1.0, smoothstep(u_fade_range.x, u_fade_range.y, distance(u_eye, position)));
  if (h0 <= -reach) return u_mist.x * share;
  float n = 2.0 * valueNoise(position.xy * u_mist_noise) - 1.0;
  float h = h0 + reach * n;
  return u_mist.x * share * (1.0 - smoothstep(0.0, 1.0, h));
}
#endif

// How much of the ink at `position` stands against the paper: 1 − the distance fade, times
// 1 − the mist, times what the border leaves. The picture is paper + (ink − paper) · this.
float presence(ObjectParams o, vec3 position) {
  float f = 1.0 - u_fade * smoothstep(u_fade_range.x, u_fade_range.y, distance(u_eye, position));
#ifdef MIST
  f *= 1.0 - mistAt(position);
#endif
#ifdef BORDER
  f *= borderPresence(o, position);
#endif
  return f;
}
