#version 450 core
// The image pass of the ink renderer: feature lines (seed 001 Eq. 1), interior shading
// (Eqs. 2, 3, 5) and the composite on paper, in one pass over the G-buffer so each pixel is
// read once. Variants: LINES and SHADING (some object uses them), WRINKLE (some object has a
// wrinkle texture), SINGLE_OBJECT (parameters without indexing), CANVAS (the paper grain,
// when no diffusion pass comes after), DEBUG_OUTPUTS (line weight and tone as extra targets,
// for tests).
#include "ink_objects.glsl"
#ifdef SHADING
#include "ink_gaussian_cdf.glsl"
#endif
#if defined(BORDER) || defined(MIST)
// Tiled fractal value noise in [0, 1] (libs/noise's erosion noise, 4 coarsest cells per
// tile): one filtered fetch costs a fraction of procedural noise on a software rasteriser.
layout(binding = 3) uniform sampler2D u_value_noise;
#endif

// The G-buffer's colour targets are read as images: llvmpipe's image load is about a third
// of the cost of a texel fetch (the ink pass ~10 % cheaper, measured side by side). The
// depth buffer cannot be an image and stays a texture.
layout(rgba16, binding = 0) readonly uniform image2D u_normal_curvature;  // encoded: see ink_gbuffer.frag
layout(rgba8, binding = 1) readonly uniform image2D u_surface_id;
layout(binding = 2) uniform sampler2D u_depth;
uniform mat4 u_inverse_view_projection;
uniform vec3 u_eye;
uniform vec2 u_near_far;     // of the projection, for linear depth
uniform vec3 u_light_dir;    // unit, towards the light
uniform vec3 u_paper;
uniform float u_fade;        // strength, [0, 1]
uniform vec2 u_fade_range;   // distances where the fade starts and is full
#ifdef MIST
uniform vec4 u_mist;         // density, z of the full mist's top, thinning band, noise amplitude (world units)
uniform float u_mist_noise;  // noise tiles per world unit
#endif
#ifdef CANVAS
layout(r32f, binding = 2) readonly uniform image2D u_canvas;  // unit-variance paper noise
uniform float u_canvas_contrast;
#endif

layout(location = 0) out vec4 o_colour;
#ifdef DEBUG_OUTPUTS
layout(location = 1) out vec2 o_line;  // weight, col_i
layout(location = 2) out float o_tone;
#endif

vec3 worldPosition(ivec2 p, float depth) {
  vec2 ndc = (vec2(p) + 0.5) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
  vec4 w = u_inverse_view_projection * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  return w.xyz / w.w;
}

// Distance along the view axis from a depth-buffer value; background is infinitely far.
float viewDepth(float d) {
  if (d >= 1.0) return 3.0e38;
  float n = u_near_far.x, f = u_near_far.y;
  return n * f / (f - d * (f - n));
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

#ifdef LINES
// The G-buffer's encoded curvature k / (1 + k) at q (monotone in k), 0 on the background.
float curvatureCode(ivec2 q) {
  if (texelFetch(u_depth, q, 0).r >= 1.0) return 0.0;
  return imageLoad(u_normal_curvature, q).w;
}
#endif

// The paper's grain over the finished colour: brightness × (1 + contrast · noise).
vec4 onPaper(ivec2 p, vec3 colour) {
#ifdef CANVAS
  colour *= 1.0 + u_canvas_contrast * imageLoad(u_canvas, p).r;
#endif
  return vec4(clamp(colour, 0.0, 1.0), 1.0);
}

#ifdef BORDER
// How much of the object is left at `position` (1 inside, 0 at its horizontal border): the
// distance to the border over the falloff width, pulled inwards by up to `roughness` widths
// of noise, so the edge is an irregular wash, never a straight cut, and always paper.
float borderPresence(ObjectParams o, vec3 position) {
  if (o.border_width <= 0.0) return 1.0;
  vec4 w = vec4(position, 1.0);
  vec2 m = vec2(dot(o.world_to_model_x, w), dot(o.world_to_model_y, w));
  vec2 inside = o.half_extent.xy - abs(m);
  float t = min(inside.x, inside.y) / o.border_width;
  if (t >= 1.0 + o.border_roughness) return 1.0;  // beyond the band the noise can reach: no noise
  // About one coarse noise cell per border width.
  float n = texture(u_value_noise, m / o.border_width * 0.25).r;
  return smoothstep(0.0, 1.0, t - o.border_roughness * n);
}
#endif

#ifdef MIST
// Mist at `position`: full below u_mist.y, thinning over u_mist.z above it, the band broken
// by noise so it lies in banks.
float mistAt(vec3 position) {
  // Noise moves the band by at most u_mist.w: outside that, no noise is needed.
  float h0 = (position.z - u_mist.y) / u_mist.z, reach = u_mist.w / u_mist.z;
  if (h0 >= 1.0 + reach) return 0.0;
  if (h0 <= -reach) return u_mist.x;
  float n = 2.0 * texture(u_value_noise, position.xy * u_mist_noise).g - 1.0;
  float h = h0 + reach * n;
  return u_mist.x * (1.0 - smoothstep(0.0, 1.0, h));
}
#endif

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
#ifdef DEBUG_OUTPUTS
  o_line = vec2(0.0, 1.0);
  o_tone = 1.0;
#endif
  // Background where nothing was drawn; the colour targets are not cleared, so they are
  // read only after this test.
  float depth = texelFetch(u_depth, p, 0).r;
  if (depth >= 1.0) {
    o_colour = onPaper(p, u_paper);
    return;
  }
  vec4 surface = imageLoad(u_surface_id, p);
  int id = int(surface.a * 255.0 + 0.5);
#ifdef SINGLE_OBJECT
  ObjectParams o = objects[0];  // a constant index: one load for all pixels, not a gather
#else
  ObjectParams o = objects[id - 1];
#endif
  vec3 position = worldPosition(p, depth);
  vec4 nc = imageLoad(u_normal_curvature, p);
  vec3 n = normalize(nc.xyz * 2.0 - 1.0);
  // k / (1 + k) back to k; the largest code stands for 65534, not infinity (no 0 · ∞).
  float k = nc.w / (1.0 - min(nc.w, 65534.0 / 65535.0));

  // Feature lines: col = 1 − k·R_CurveFactor, a line where col < Curv0 (smoothstep of the
  // soft width), silhouettes where N·V is small, outlines where the depth jumps away.
  float line_weight = 0.0, col = 1.0;
#ifdef LINES
  if ((o.line_flags & kLinesOn) != 0u) {
    col = 1.0 - k * o.curve_factor;
    float threshold = o.line_threshold, soft = o.soft_width;
    if ((o.line_flags & kNormalOnly) == 0u) {
      line_weight = soft > 0.0 ? 1.0 - smoothstep(threshold - 0.5 * soft, threshold + 0.5 * soft, col)
                               : (col < threshold ? 1.0 : 0.0);
      // Thin lines: of the pixels past the threshold keep those where the curvature peaks
      // across the line (non-maximum suppression along the axis where it changes most), so
      // a broad band of high curvature draws its crest, not a filled shape.
      if ((o.line_flags & kThinLines) != 0u && line_weight > 0.0) {
        float l = curvatureCode(p - ivec2(1, 0)), r = curvatureCode(p + ivec2(1, 0));
        float d = curvatureCode(p - ivec2(0, 1)), u = curvatureCode(p + ivec2(0, 1));
        bool peak = abs(r - l) >= abs(u - d) ? nc.w >= max(l, r) : nc.w >= max(d, u);
        if (!peak) line_weight = 0.0;
      }
    }
    float silhouette = o.silhouette;
    if (silhouette > 0.0) {
      float n_dot_v = abs(dot(n, normalize(u_eye - position)));
      line_weight = max(line_weight, 1.0 - smoothstep(0.5 * silhouette, silhouette, n_dot_v));
    }
    float jump = o.depth_edges;
    if (jump > 0.0) {
      float z = viewDepth(depth);
      if (viewDepth(farthestNeighbour(p)) - z > jump * z) line_weight = 1.0;
    }
    col = clamp(col, 0.0, 1.0);
  }
#endif

  // Interior shading: diffuse term eroded by noise, or by the wrinkle texture where the
  // lines left background (Eq. 3, β a parameter), times col_i, plus noise, then five tones
  // with Gaussian-smoothed steps.
  float tone = 1.0;
#ifdef SHADING
  uint shade_flags = o.shade_flags;
  if ((shade_flags & kShadingOn) != 0u) {
    float n_dot_l = dot(n, u_light_dir);
    float t_d = (shade_flags & kHalfLambert) != 0u ? 0.5 * n_dot_l + 0.5 : max(n_dot_l, 0.0);
    float t_w = 1.0 - o.erosion * (1.0 - surface.r);
#ifdef WRINKLE
    if ((shade_flags & kWrinkled) != 0u && line_weight < 0.5) t_w = surface.b * o.inv_inner_tex_factor;
#endif
    float t = clamp(t_d + t_w + o.beta, 0.0, 1.0);
    if ((shade_flags & kLineValue) != 0u) t *= col;
    t += o.noise * (2.0 * surface.g - 1.0);
    float sigma = o.sigma;
    float c[5] = float[5](o.tones.x, o.tones.y, o.tones.z, o.tones.w, o.tone5);
    tone = c[0];
    for (int k = 0; k < 4; ++k) {
      // Φ only near the step: beyond 6σ it is 0 or 1 to within 1e-9.
      float x = sigma > 0.0 ? (t - o.thresholds[k]) / sigma : (t > o.thresholds[k] ? 7.0 : -7.0);
      float s = abs(x) < 6.0 ? gaussianCdf(x) : step(0.0, x);
      tone += (c[k + 1] - c[k]) * s;
    }
  }
#endif

  // Composite: ink on paper, lines over the interior, far surfaces fading into the paper.
  vec3 colour = mix(u_paper * o.bg_color * tone, o.line_color, line_weight);
  float fade = u_fade * smoothstep(u_fade_range.x, u_fade_range.y, distance(u_eye, position));
  colour = mix(colour, u_paper, fade);
#ifdef MIST
  colour = mix(colour, u_paper, mistAt(position));
#endif
#ifdef BORDER
  colour = mix(u_paper, colour, borderPresence(o, position));
#endif
  o_colour = onPaper(p, colour);
#ifdef DEBUG_OUTPUTS
  o_line = vec2(line_weight, col);
  o_tone = tone;
#endif
}
