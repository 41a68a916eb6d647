#version 450 core
// The image pass of the ink renderer: feature lines (seed 001 Eq. 1), interior shading
// (Eqs. 2, 3, 5) and the composite on paper, in one pass over the G-buffer so each pixel is
// read once. Variants: LINES and SHADING (some object uses them), STROKES (some object draws
// its lines as strokes: the centres come from ink_lines.frag), BAND_LINES (some object draws
// Eq. 1's bands, silhouettes and outlines here, without strokes), WRINKLE (some object has a
// wrinkle texture), WRINKLE_SLOPE (an object's slope wrinkles on planar UVs are computed
// here, once per pixel, not in the G-buffer pass), SINGLE_OBJECT (parameters without
// indexing), CANVAS (the paper grain, when no diffusion pass comes after), PIGMENT (the
// presence the atmosphere leaves, in alpha, for the pigment pass), ELEMENTS (the trees' and
// moss dots' ink over the rest; ELEMENT_NEARNESS with animated objects), WATER (a water level:
// the land below it hidden, paper with wave strokes, bank lines), MARKS (some object's
// texture strokes as discrete marks, ink_marks.glsl; WASH: some object's broad wet strokes),
// STROKE_GATHER (compute only: each pixel gathers the strokes' ink from the centres near it),
// DEBUG_OUTPUTS (line weight, tone and wrinkle luma as extra targets, for tests). PAPER
// builds the background's program, which the pass draws apart by the depth test; BARE the
// surfaces' where the atmosphere leaves nothing of the land (ink_classes.frag sorts them out
// for a fragment pass). With PIXEL_COMPUTE the surfaces' and the background's are compute shaders
// (pixel_main.glsl) testing the depth themselves; DEBUG_OUTPUTS stays a fragment pass.
#include "pixel_stage.glsl"
#include "ink_objects.glsl"
#ifdef SHADING
#include "ink_gaussian_cdf.glsl"
#endif
#include "ink_surface.glsl"
#ifdef STROKES
// The strokes' ink × 255, stamped by ink_lines.frag (with STROKE_GATHER each centre's ink
// and reach, gathered here), and the presence and shading noise it found per surface pixel.
#ifdef STROKE_GATHER
layout(rg32f, binding = 3) readonly uniform image2D u_stroke_centre;
uniform int u_stroke_reach;  // the most pixels any centre's ink reaches (a whole number)
#else
layout(r32ui, binding = 3) readonly uniform uimage2D u_stroke_ink;
#endif
layout(rgba16, binding = 4) readonly uniform image2D u_presence_noise;
#endif
#ifdef ELEMENTS
// Trees and moss dots (elements_pass.cpp): their ink; with ELEMENT_NEARNESS (animated
// scenes) also the nearness (1 − depth) of what drew it, to hide them behind what moved in
// front of their cached layer.
uniform vec3 u_element_colour;
#ifdef ELEMENT_NEARNESS
layout(rg32f, binding = 6) readonly uniform image2D u_elements;
float elementInk(ivec2 p, float depth) {
  vec2 e = imageLoad(u_elements, p).rg;
  return e.g >= 1.0 - depth ? e.r : 0.0;
}
#else
layout(r8, binding = 6) readonly uniform image2D u_elements;
float elementInk(ivec2 p, float depth) {
  return imageLoad(u_elements, p).r;
}
#endif
#endif
#ifdef CANVAS
// The paper: unit-variance grain, and its marks (fibres, spots, mottle) as a brightness change.
layout(rg16f, binding = 2) readonly uniform image2D u_canvas;
uniform float u_canvas_contrast;
#endif

#if defined(WRINKLE_SLOPE) || defined(MARKS)
// How far the surface point moves for one pixel along `step` on screen: where that pixel's
// view ray meets the tangent plane at P (normal n), less P. For a surface of planar UVs it
// stands in for the screen derivatives of position the G-buffer pass takes from the
// triangle. A ray grazing the plane is held to a long but finite step.
vec3 tangentStep(ivec2 p, vec2 step, vec3 P, vec3 n) {
  vec2 ndc = (vec2(p) + 0.5 + step) / vec2(textureSize(u_depth, 0)) * 2.0 - 1.0;
  vec4 a = u_inverse_view_projection * vec4(ndc, -1.0, 1.0), b = u_inverse_view_projection * vec4(ndc, 1.0, 1.0);
  vec3 o = a.xyz / a.w, d = b.xyz / b.w - o;
  float dn = dot(d, n), least = 1e-6 * length(d);
  return o + dot(P - o, n) / (abs(dn) > least ? dn : least) * d - P;
}
#endif

#ifdef WRINKLE_SLOPE
layout(binding = 4) uniform sampler2D u_wrinkle;  // Eq. 5's luma, mipmapped
#include "ink_wrinkle.glsl"

// The slope wrinkles at P of an object with planar UVs: its model x and y from the box's
// low corner over the box's larger horizontal side (scene_assets.cpp's planarUvs), through
// the world-to-model rows the border uses.
float planarSlopeWrinkle(ObjectParams o, ivec2 p, vec3 P, vec3 n) {
  vec3 dpx = tangentStep(p, vec2(1.0, 0.0), P, n), dpy = tangentStep(p, vec2(0.0, 1.0), P, n);
  float per_unit = 0.5 / max(max(o.half_extent.x, o.half_extent.y), 1e-30);
  vec3 ux = o.world_to_model_x.xyz * per_unit, uy = o.world_to_model_y.xyz * per_unit;
  vec2 uv = vec2(dot(ux, P) + o.world_to_model_x.w * per_unit, dot(uy, P) + o.world_to_model_y.w * per_unit) +
            o.half_extent.xy * per_unit;
  return slopeWrinkle(u_wrinkle, n, uv, dpx, dpy, vec2(dot(ux, dpx), dot(uy, dpx)), vec2(dot(ux, dpy), dot(uy, dpy)),
                      o.wrinkle_tile_px, o.wrinkle_angle);
}
#endif

#ifdef MARKS
#include "ink_marks.glsl"

// Texture marks at P of object o (normal n, curvature k): the lattice lies on the object's
// horizontal plane (model x, y), the marks run down the fall line turned by marks_angle, and
// their density grows from marks_lit of it on lit slopes to all of it in shadow and near
// ridges; flat ground stays bare. With WASH, the broad wet strokes (wash_*) over them, on a
// lattice of their own on the picture plane of the scene's view, dense where the slope turns
// from the light (wash_lit of that on lit slopes) and where the atmosphere leaves the land
// (here).
float objectMarks(ObjectParams o, ivec2 p, vec3 P, vec3 n, float k, float here) {
  vec3 down = vec3(0.0, 0.0, -1.0) + n.z * n;
  float steep = smoothstep(0.2, 0.45, length(down));
  float shade = 1.0 - max(dot(n, u_light_dir), 0.0);
  float c = cos(o.marks_angle), s = sin(o.marks_angle);
  mat2 turn = mat2(c, s, -s, c);
  float ink = 0.0;
  float density = o.marks_density * steep * mix(o.marks_lit, 1.0, shade) * (1.0 + o.marks_ridge * clamp(abs(k), 0.0, 1.0));
  if (o.marks_style != 0u && density > 0.0) {
    vec3 dpx = tangentStep(p, vec2(1.0, 0.0), P, n), dpy = tangentStep(p, vec2(0.0, 1.0), P, n);
    vec3 mx = o.world_to_model_x.xyz, my = o.world_to_model_y.xyz;
    vec2 uv = vec2(dot(mx, P) + o.world_to_model_x.w, dot(my, P) + o.world_to_model_y.w);
    float scale = marksScale(vec2(dot(mx, dpx), dot(my, dpx)), vec2(dot(mx, dpy), dot(my, dpy)), o.marks_spacing_px);
    ink = o.marks_ink * textureMarks(uv, scale, turn * vec2(dot(mx, down), dot(my, down)), min(density, 1.0),
                                     o.marks_style, o.marks_seed);
  }
#ifdef WASH
  // Wet strokes thin out with what the atmosphere leaves of the land, as a painter leaves the
  // mist at a range's foot unbrushed: none where under a twentieth is left. A loop of at most
  // one turn, not a branch (ink_marks.glsl), so pixels without them cost nothing.
  float wash = o.wash_density * smoothstep(0.02, 0.12, length(down)) *
               mix(o.wash_lit, 1.0, smoothstep(0.2, 0.6, shade)) * smoothstep(0.05, 0.4, here);
  for (int i = wash > 0.0 ? 0 : 1; i < 1; ++i) {
    // On the picture plane of the scene's view, in cells of one size over the object, down
    // the fall line as it looks there (on gentle ground, where that wanders, leaning to
    // straight down the sheet) or, by wash_follow, straight down the sheet: on rough ground
    // the fall line turns from pixel to pixel and breaks a stroke into blotches.
    vec3 r = u_brush_right, u = u_brush_up;
    vec2 fall = vec2(dot(r, down), dot(u, down) - 0.1);
    fall = length(fall) > 1e-6 ? normalize(fall) : vec2(0.0, -1.0);
    ink += (1.0 - ink) * o.wash_ink *
           washMarks(vec2(dot(r, P), dot(u, P)), o.wash_cell, turn * mix(vec2(0.0, -1.0), fall, o.wash_follow),
                     min(wash, 1.0), o.wash_width, o.marks_seed ^ 0x5bd1e995u);
  }
#endif
  return ink;
}
#endif

#ifdef PIXEL_COMPUTE
layout(rgba8, binding = 7) writeonly uniform image2D u_colour_out;
vec4 o_colour;
void pixelOutputsClear() { o_colour = vec4(0.0); }
void pixelStore(ivec2 p) { imageStore(u_colour_out, p, o_colour); }
#else
layout(location = 0) out vec4 o_colour;
#endif
#ifdef WATER
#include "ink_water.glsl"
#endif

#ifdef DEBUG_OUTPUTS
layout(location = 1) out vec2 o_line;  // weight, col_i
layout(location = 2) out vec2 o_tone;  // tone, wrinkle luma (1 without wrinkles)
#endif

// The paper over the finished colour: brightness × (1 + contrast · grain) × (1 + marks).
vec4 onPaper(ivec2 p, vec3 colour) {
#ifdef CANVAS
  vec2 paper = imageLoad(u_canvas, p).rg;
  colour *= (1.0 + u_canvas_contrast * paper.r) * (1.0 + paper.g);
#endif
  return vec4(clamp(colour, 0.0, 1.0), 1.0);
}

#ifdef STROKES
#ifdef STROKE_GATHER
// What the most inking centre within reach gives p: the ink a centre q stamps at p + (q − p)
// in ink_lines.frag, by the same expression (the disc's antialiased edge leaves nothing
// beyond its reach, so the square around p holds every centre that inks it). Centres off
// the image read as 0.
float strokeInk(ivec2 p) {
  uint best = 0u;
  for (int dy = -u_stroke_reach; dy <= u_stroke_reach; ++dy) {
    for (int dx = -u_stroke_reach; dx <= u_stroke_reach; ++dx) {
      vec2 c = imageLoad(u_stroke_centre, p - ivec2(dx, dy)).rg;  // ink, reach
      float cover = clamp(c.y - length(vec2(dx, dy)), 0.0, 1.0);
      best = max(best, uint(c.x * cover * 255.0 + 0.5));
    }
  }
  return float(best) / 255.0;
}
#else
float strokeInk(ivec2 p) {
  return float(imageLoad(u_stroke_ink, p).r) / 255.0;
}
#endif
#endif

// Depth-tested against the G-buffer's depth before shading: the pass draws the surfaces
// and the background (PAPER) apart, each with its own main.
#ifndef PIXEL_COMPUTE
layout(early_fragment_tests) in;
#endif

#ifdef PAPER
// Where nothing was drawn: the paper, and the outlines' ink that overran the silhouette.
void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
  float ink = 0.0;
#ifdef STROKES
  ink = strokeInk(p);
#endif
  vec3 colour = mix(u_paper, objects[0].line_color, ink);
#ifdef WATER
  colour = mix(colour, objects[0].line_color, openWaterInk(p));
#endif
#ifdef ELEMENTS
  colour = mix(colour, u_element_colour, elementInk(p, 1.0));
#endif
  o_colour = onPaper(p, colour);
#ifdef DEBUG_OUTPUTS
  o_line = vec2(ink, 1.0);
  o_tone = vec2(1.0);
#endif
}
#else
// A land pixel's colour before the trees and the paper: feature lines, interior shading and
// texture marks, taken towards the paper by what the atmosphere leaves (`here`), then the
// strokes. z_per_pixel: how much the height changes to a neighbour (the bank line's reach).
vec3 landColour(ObjectParams o, ivec2 p, float depth, vec4 surface, vec3 position, float here, vec2 noise,
                float z_per_pixel) {
  vec4 nc = imageLoad(u_normal_curvature, p);
  vec3 n = normalize(nc.xyz * 2.0 - 1.0);
  float k = decodeCurvature(nc.w);

  // Feature lines: col = 1 − k·R_CurveFactor, a line where col < Curv0 (smoothstep of the
  // soft width), silhouettes where N·V is small, outlines where the depth jumps away.
  float line_weight = 0.0, col = 1.0;
#ifdef LINES
  if ((o.line_flags & kLinesOn) != 0u) {
    col = 1.0 - k * o.curve_factor;
    float threshold = o.line_threshold, soft = o.soft_width;
    // Strokes are drawn after the composite, from their centres.
#ifdef BAND_LINES
    if ((o.line_flags & kStrokes) == 0u) {
      if ((o.line_flags & kNormalOnly) == 0u) {
        line_weight = soft > 0.0 ? 1.0 - smoothstep(threshold - 0.5 * soft, threshold + 0.5 * soft, col)
                                 : (col < threshold ? 1.0 : 0.0);
        // Thin lines: of the pixels past the threshold keep those where the curvature peaks
        // across the line (non-maximum suppression along the axis where it bends down most), so
        // a broad band of high curvature draws its crest, not a filled shape.
        if ((o.line_flags & kThinLines) != 0u && line_weight > 0.0) {
          float l = curvatureCode(p - ivec2(1, 0)), r = curvatureCode(p + ivec2(1, 0));
          float d = curvatureCode(p - ivec2(0, 1)), u = curvatureCode(p + ivec2(0, 1));
          bool peak = l + r <= d + u ? nc.w >= max(l, r) : nc.w >= max(d, u);
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
    }
#endif
    col = clamp(col, 0.0, 1.0);
  }
#endif
#ifdef WATER
  line_weight = max(line_weight, bankLine(p, position, z_per_pixel));
#endif

  // Interior shading: diffuse term eroded by noise, or by the wrinkle texture where the
  // lines left background (Eq. 3, β a parameter), times col_i, plus noise, then five tones
  // with Gaussian-smoothed steps.
  float tone = 1.0, wrinkle = 1.0;
#ifdef SHADING
  uint shade_flags = o.shade_flags;
  if ((shade_flags & kShadingOn) != 0u) {
    float n_dot_l = dot(n, u_light_dir);
    float t_d = (shade_flags & kHalfLambert) != 0u ? 0.5 * n_dot_l + 0.5 : max(n_dot_l, 0.0);
    float t_w = 1.0 - o.erosion * (1.0 - noise.r);
#ifdef WRINKLE
    wrinkle = surface.b;
#ifdef WRINKLE_SLOPE
    if ((shade_flags & kWrinkleHere) != 0u) wrinkle = planarSlopeWrinkle(o, p, position, n);
#endif
    if ((shade_flags & kWrinkled) != 0u && line_weight < 0.5) t_w = wrinkle * o.inv_inner_tex_factor;
#endif
    float t = clamp(t_d + t_w + o.beta, 0.0, 1.0);
    if ((shade_flags & kLineValue) != 0u) t *= col;
    t += o.noise * (2.0 * noise.g - 1.0);
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

  // Composite: ink on paper, lines over the interior, then the atmosphere and the border
  // take it back towards the paper; strokes carry their own.
  vec3 colour = mix(u_paper * o.bg_color * tone, o.line_color, line_weight);
#ifdef MARKS
  if (o.marks_style != 0u || o.wash_density > 0.0)
    colour = mix(colour, o.line_color, objectMarks(o, p, position, n, k, here));
#endif
  colour = mix(u_paper, colour, here);
#ifdef STROKES
  float stroke = strokeInk(p);
  colour = mix(colour, o.line_color, stroke);
  line_weight = max(line_weight, stroke);
#endif
#ifdef DEBUG_OUTPUTS
  o_line = vec2(line_weight, col);
  o_tone = vec2(tone, wrinkle);
#endif
  return colour;
}

void shadePixel() {
  ivec2 p = ivec2(PIXEL_COORD);
#ifdef DEBUG_OUTPUTS
  o_line = vec2(0.0, 1.0);
  o_tone = vec2(1.0);
#endif
  float depth = texelFetch(u_depth, p, 0).r;
  vec4 surface = imageLoad(u_surface_id, p);
  int id = int(surface.a * 255.0 + 0.5);
#ifdef SINGLE_OBJECT
  ObjectParams o = objects[0];  // a constant index: one load for all pixels, not a gather
#else
  ObjectParams o = objects[id - 1];
#endif
  vec3 position = worldPosition(p, depth);
  // Where the atmosphere is taken: the point shown, or the water's surface above land under
  // water (which is hidden).
  vec3 atmosphere_at = position;
  bool under = false;
  float z_per_pixel = 0.0;
#ifdef WATER
  under = underWater(position);
  atmosphere_at.z = max(position.z, u_water.x);
  // How much the height changes from pixel to pixel here (taken before any branch), so the
  // bank line looks at its neighbours only near the water's level.
#ifdef PIXEL_COMPUTE
  // A compute shader has no derivatives: the differences across p's 2x2 quad, along its row
  // and its column, as a fragment shader's fine derivatives take them.
  ivec2 q = p & ~1;
  float dx = worldPositionAt(ivec2(q.x + 1, p.y)).z - worldPositionAt(ivec2(q.x, p.y)).z;
  float dy = worldPositionAt(ivec2(p.x, q.y + 1)).z - worldPositionAt(ivec2(p.x, q.y)).z;
  z_per_pixel = max(abs(dx), abs(dy));
#else
  z_per_pixel = max(abs(dFdx(position.z)), abs(dFdy(position.z)));
#endif
#endif
#ifdef BARE
  // Only where the atmosphere leaves nothing (the pass's depth test picks these pixels).
  float here = 0.0;
  vec2 noise = vec2(0.0);
#elif defined(STROKES)
  // The lines pass took the presence at atmosphere_at, the noise at the point shown.
  vec4 presence_noise = imageLoad(u_presence_noise, p);
  float here = presence_noise.r;
  vec2 noise = presence_noise.gb;
#else
  float here = presence(o, atmosphere_at);
  vec2 noise = surfaceNoise(o, position);
#endif
  // Bare: nothing of the land stands (a dissolved border), so it shows the paper and the
  // strokes that overran onto it, as landColour would at here = 0, without its work (the
  // debug outputs want that work's lines and tones).
  bool bare = here <= 0.0;
#ifdef DEBUG_OUTPUTS
  bare = false;
#endif
  vec3 colour = u_paper;
  if (under) {
#ifdef WATER
    // The land under the water is hidden: paper and the waves (their share 0 elsewhere, so a
    // software rasteriser, which runs this for the whole group of pixels, turns no cells).
    colour = mix(u_paper, o.line_color, waveInk(p, under ? here : 0.0));
#endif
  } else if (bare) {
#ifdef STROKES
    colour = mix(u_paper, o.line_color, strokeInk(p));
#endif
  } else {
    colour = landColour(o, p, depth, surface, position, here, noise, z_per_pixel);
  }
#ifdef ELEMENTS
  colour = mix(colour, u_element_colour, elementInk(p, depth));
#endif
  o_colour = onPaper(p, colour);
#ifdef PIGMENT
  o_colour.a = under ? 0.0 : here;  // the pigment pass thins its wash as the atmosphere thins the ink; none on water
#endif
}
#endif
#include "pixel_main.glsl"
