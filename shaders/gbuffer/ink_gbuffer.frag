#version 450 core
// G-buffer pass: world normal and dimensionless curvature (|k| times the mesh's feature
// size), and the surface detail the shading reads, with the object id. Curvature is either
// interpolated from the vertices (OBJECT_CURVATURE) or, as seed 001 does, estimated in
// screen space from how fast the normal turns per unit of surface, |fwidth(N)| / |fwidth(P)|
// (SCREEN_CURVATURE); objects without lines get neither. World positions are not stored:
// the image passes rebuild them from the depth buffer.
in vec3 v_normal;
#ifdef WRINKLE
in vec2 v_uv;
uniform sampler2D u_wrinkle;   // Eq. 5's luma of the wrinkle texture, mipmapped
uniform float u_repeat;        // texture repetitions per UV unit
#endif
#ifdef OBJECT_CURVATURE
in float v_curvature;
#endif
#if defined(SCREEN_CURVATURE) || defined(WRINKLE_SLOPE)
in vec3 v_world;
#endif
#ifdef SCREEN_CURVATURE
uniform float u_feature_size;  // world units
#endif
#ifdef WRINKLE_SLOPE
uniform float u_tile_px;  // a texture tile's size on screen, pixels
uniform float u_angle;    // radians: the texture's v axis turned from the fall line
#include "ink_wrinkle.glsl"
#endif
#ifdef SURFACE
in vec2 v_noise_uv;
uniform sampler2D u_noise;     // r: erosion noise, g: noise added before quantisation
#endif
uniform float u_object_id;     // (index + 1) / 255

layout(location = 0) out vec4 o_normal_curvature;  // RGBA16: n / 2 + 1/2, k / (1 + k)
layout(location = 1) out vec4 o_surface_id;  // erosion noise (SURFACE), added noise, wrinkle luma, id
#ifdef VELOCITY
// Seed 004's velocity buffer: how far this point moved on screen since the previous frame,
// in pixels; alpha 1 marks a surface (the target is cleared to 0).
in vec4 v_clip;
in vec4 v_previous_clip;
// The camera, the atmosphere, the paper: the frame's block.
#include "frame.glsl"
layout(location = 2) out vec4 o_velocity;
#endif

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  float k = 0.0;
#ifdef OBJECT_CURVATURE
  k = v_curvature;
#endif
#ifdef SCREEN_CURVATURE
  float dp = length(fwidth(v_world));
  k = dp > 0.0 ? length(fwidth(n)) / dp * u_feature_size : 0.0;
#endif
  // Unsigned normalised 16 bits (half floats cost a software rasteriser a conversion per
  // channel): the normal's components from [-1, 1], the curvature (never negative) from
  // [0, ∞) with k / (1 + k), relative precision ~1e-4 up to k ≈ 10 (ink.frag decodes).
  o_normal_curvature = vec4(n * 0.5 + 0.5, max(k, 0.0) / (1.0 + max(k, 0.0)));
  vec2 noise = vec2(1.0, 0.5);  // no erosion, nothing added
#ifdef SURFACE
  noise = texture(u_noise, v_noise_uv).rg;
#endif
  float wrinkle = 1.0;
#if defined(WRINKLE_SLOPE)
  wrinkle = slopeWrinkle(u_wrinkle, n, v_uv, dFdx(v_world), dFdy(v_world), dFdx(v_uv), dFdy(v_uv), u_tile_px, u_angle);
#elif defined(WRINKLE)
  wrinkle = texture(u_wrinkle, v_uv * u_repeat).r;
#endif
  o_surface_id = vec4(noise, wrinkle, u_object_id);
#ifdef VELOCITY
  vec2 now = v_clip.xy / v_clip.w, before = v_previous_clip.xy / v_previous_clip.w;
  o_velocity = vec4((now - before) * 0.5 * u_viewport, 0.0, 1.0);
#endif
}
