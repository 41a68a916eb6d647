#version 450 core
// G-buffer pass. Curvature is dimensionless (|k| times the mesh's feature size): either
// interpolated from the vertices (OBJECT_CURVATURE) or, as seed 001 does, estimated in
// screen space from how fast the normal turns per unit of surface, |fwidth(N)| / |fwidth(P)|
// (SCREEN_CURVATURE); objects without lines get neither.
in vec3 v_world;
in vec3 v_normal;
in vec3 v_model;
#ifdef WRINKLE
in vec2 v_uv;
uniform sampler2D u_wrinkle;   // Eq. 5's luma of the wrinkle texture, mipmapped
uniform float u_repeat;        // texture repetitions per UV unit
#endif
#ifdef OBJECT_CURVATURE
in float v_curvature;
#endif
#ifdef SCREEN_CURVATURE
uniform float u_feature_size;  // world units
#endif
#ifdef SURFACE
uniform sampler2D u_noise;          // r: erosion noise, g: noise added before quantisation
uniform float u_noise_frequency;    // noise texture repetitions per model unit
#endif
uniform float u_object_id;          // index + 1; 0 is the background

layout(location = 0) out vec4 o_normal_curvature;
layout(location = 1) out vec4 o_position_id;
#ifdef SURFACE
layout(location = 2) out vec4 o_surface;  // erosion noise, added noise, wrinkle luma, 1
#endif

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  float k = 0.0;  // objects without lines
#ifdef OBJECT_CURVATURE
  k = v_curvature;
#endif
#ifdef SCREEN_CURVATURE
  float dp = length(fwidth(v_world));
  k = dp > 0.0 ? length(fwidth(n)) / dp * u_feature_size : 0.0;
#endif
  o_normal_curvature = vec4(n, k);
  o_position_id = vec4(v_world, u_object_id);
#ifdef SURFACE
  vec2 noise = texture(u_noise, v_model.xy * u_noise_frequency).rg;
  float wrinkle = 1.0;
#ifdef WRINKLE
  wrinkle = texture(u_wrinkle, v_uv * u_repeat).r;
#endif
  o_surface = vec4(noise, wrinkle, 1.0);
#endif
}
