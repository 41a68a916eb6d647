// The frame's uniforms that several passes read alike (the camera, the distance fade, the
// mist, the water, the light, the paper), defined once for GLSL (frame.glsl) and C++
// (libs/render/include/shanshui/render/frame_params.h). The renderer fills the block once a
// frame and binds it for every pass (issue 47: per-frame uniforms in blocks, not one call
// per uniform and program). Members are mat4s, vec4s, vec3 + scalar pairs, vec2 pairs and
// scalars, so std140 places each where C++ does; a GL test compares every offset with the
// driver's.
#define SHANSHUI_FRAME_PARAMS(F) \
  F(mat4, u_view_projection) \
  F(mat4, u_inverse_view_projection) \
  F(vec3, u_eye)            F(float, u_fade) \
  F(vec3, u_light_dir)      F(float, u_mist_noise) \
  F(vec3, u_paper)          F(float, u_mist_near) \
  F(vec4, u_mist) \
  F(vec4, u_water) \
  F(vec4, u_water_extent) \
  F(vec2, u_near_far)       F(vec2, u_fade_range) \
  F(vec2, u_viewport)       F(vec2, u_water_right) \
  F(float, u_water_bank)    F(float, u_pixel_angle) F(float, u_water_bank_break) F(float, u_frame_unused1) \
  F(vec3, u_brush_right)    F(float, u_frame_unused2) \
  F(vec3, u_brush_up)       F(float, u_frame_unused3)

// u_view_projection: the camera's projection × view (world to clip), u_inverse_view_projection
// its inverse; u_eye: the camera's position (world); u_fade: the distance fade's strength and
// u_fade_range the distances where it starts and is full (the scene's nearest and farthest
// bounding-box corners from the eye); u_light_dir: unit, towards the light; u_mist_noise:
// the mist's noise tiles per world unit; u_paper: the paper's colour; u_mist_near: the share
// of the mist on the nearest land; u_mist: density, z of the full mist's top, thinning band,
// noise amplitude (world units; all 0 without mist); u_water: level (world z; the lowest
// float without water), wave cell (world units), share of cells with a stroke, ink;
// u_water_extent: the open water's rectangle in world xy (min, max); u_near_far: the
// projection's planes; u_viewport: the frame's size in pixels; u_water_right: the picture's
// horizontal laid on the water (unit, world xy); u_water_bank: the bank line's width in
// pixels; u_water_bank_break: how far it breaks into strokes along the shore (0: even); u_pixel_angle: a pixel's height at distance 1 (world units); u_brush_right,
// u_brush_up: the picture plane of the scene's own view (camera.azimuth and elevation, unit,
// world), where the broad wet strokes lie (ink_marks.glsl), so a painter's strokes keep their
// shape on a slope facing the viewer and stay fixed in the world when the view turns.
