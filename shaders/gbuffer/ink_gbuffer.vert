#version 450 core
// G-buffer pass. Only what the variant needs is interpolated (llvmpipe pays per varying):
// normal always; erosion-noise coordinates (SURFACE: for the pigment wash), UVs (WRINKLE),
// per-vertex curvature (OBJECT_CURVATURE), world position for screen-space derivatives
// (SCREEN_CURVATURE, WRINKLE_SLOPE); clip positions now and a frame ago (VELOCITY).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#ifdef WRINKLE
layout(location = 2) in vec2 a_uv;
out vec2 v_uv;
#endif
#ifdef OBJECT_CURVATURE
layout(location = 3) in float a_curvature;
out float v_curvature;
#endif
#if defined(SCREEN_CURVATURE) || defined(WRINKLE_SLOPE)
out vec3 v_world;
#endif
#ifdef SURFACE
uniform float u_noise_frequency;  // noise texture repetitions per model unit
out vec2 v_noise_uv;
#endif

#ifdef VELOCITY
uniform mat4 u_previous_model_view_projection;  // the previous frame's pose and camera
out vec4 v_clip;
out vec4 v_previous_clip;
#endif
uniform mat4 u_model;
uniform mat3 u_normal_matrix;
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"

out vec3 v_normal;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_normal = u_normal_matrix * a_normal;
#ifdef WRINKLE
  v_uv = a_uv;
#endif
#ifdef OBJECT_CURVATURE
  v_curvature = a_curvature;
#endif
#if defined(SCREEN_CURVATURE) || defined(WRINKLE_SLOPE)
  v_world = world.xyz;
#endif
#ifdef SURFACE
  v_noise_uv = a_position.xy * u_noise_frequency;  // fixed to the model: moves with it
#endif
  gl_Position = u_view_projection * world;
#ifdef VELOCITY
  v_clip = gl_Position;
  v_previous_clip = u_previous_model_view_projection * vec4(a_position, 1.0);
#endif
}
