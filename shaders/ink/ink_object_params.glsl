// Per-object parameters of the ink pass, defined once for GLSL (ink_objects.glsl) and C++
// (libs/render/include/shanshui/render/ink_object_params.h): names, order and flag bits
// cannot drift apart. Members are vec4s, scalars and vec3 + scalar pairs, so std140 and
// std430 place each where C++ does (a vec3 starts a 16-byte slot and the scalar after it
// fills the slot); the C++ side checks this statically and a GL test compares every
// offset with the driver's.
#define SHANSHUI_OBJECT_PARAMS(F) \
  F(vec3, line_color)     F(float, curve_factor) \
  F(vec3, bg_color)       F(float, line_threshold) \
  F(float, soft_width)    F(float, silhouette)   F(float, depth_edges)          F(uint, line_flags) \
  F(vec4, tones)  \
  F(vec4, thresholds) \
  F(float, tone5)         F(float, sigma)        F(float, beta)                 F(float, erosion) \
  F(float, noise)         F(float, inv_inner_tex_factor) F(uint, shade_flags)   F(float, border_roughness) \
  F(vec4, world_to_model_x) \
  F(vec4, world_to_model_y) \
  F(vec3, half_extent)    F(float, border_width) \
  F(float, stroke_half_width) F(float, stroke_taper) F(float, stroke_far) F(float, valley_ink) \
  F(float, suggestive)    F(float, wrinkle_tile_px) F(float, wrinkle_angle)     F(float, noise_frequency) \
  F(float, marks_ink)     F(float, marks_density) F(float, marks_spacing_px)    F(float, marks_lit) \
  F(float, marks_ridge)   F(uint, marks_style)   F(uint, marks_seed)            F(float, marks_angle) \
  F(float, wash_ink)      F(float, wash_density) F(float, wash_cell)           F(float, wash_lit) \
  F(float, wash_follow)   F(float, wash_width)   F(float, line_break)          F(float, line_break_cell)

// world_to_model_x/y: rows of the world-to-model affine map (x and y of the model, relative
// to its bounding-box centre); half_extent: the box's half size; border_width: the
// dissolving border's falloff in model units (0 = a hard edge). stroke_half_width: half the
// stroke width in pixels (0 = Eq. 1's bands); stroke_taper, stroke_far, valley_ink,
// suggestive: see LineParams; wrinkle_tile_px, wrinkle_angle: the slope wrinkles' tile size
// on screen (pixels) and turn (radians) where the ink pass computes them (kWrinkleHere);
// noise_frequency: erosion-noise tiles per model unit (x and y as world_to_model_x/y give them).
// marks_*: the texture marks (objects.N.marks; ink_marks.glsl): ink, density on the darkest
// ground, lattice spacing on screen (pixels), density on lit slopes relative to shadow, the
// extra near ridges, style (0 none, kMarksHemp, kMarksAxe), seed, turn from the fall line.
// wash_*: the broad wet strokes (objects.N.marks.wash*): ink, density in full shadow (0 =
// none), log2 of their lattice's cell in world units (one size for the whole object, from its
// centre's distance), density on lit slopes relative to shadow, how far they follow the
// fall line (1) rather than run straight down the picture (0), breadth (1: three thin strokes
// apart; 2 and over: they merge into one broad side-brush stroke). line_break: objects.N.lines.break;
// line_break_cell: its noise's cell in world units (kLineBreakWidths stroke widths on screen at
// the object's centre, as wash_cell is sized).

// line_flags bits
const uint kLinesOn = 1u;
const uint kNormalOnly = 2u;  // small object: N·V and depth-edge lines only
const uint kThinLines = 4u;   // Eq. 1's lines thinned to the curvature's crest
const uint kStrokes = 8u;     // lines drawn as strokes from their centres (ink_lines.frag)
// shade_flags bits
const uint kShadingOn = 1u;
const uint kHalfLambert = 2u;
const uint kLineValue = 4u;
const uint kWrinkled = 8u;
const uint kWrinkleHere = 16u;  // slope wrinkles from planar UVs, computed in the ink pass
