#version 450 core
// G-buffer pass: world position and normal, model position for the erosion noise, and the
// attributes of the variant: UVs (WRINKLE), per-vertex curvature (OBJECT_CURVATURE).
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

uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;

out vec3 v_world;
out vec3 v_normal;
out vec3 v_model;

void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = u_normal_matrix * a_normal;
  v_model = a_position;
#ifdef WRINKLE
  v_uv = a_uv;
#endif
#ifdef OBJECT_CURVATURE
  v_curvature = a_curvature;
#endif
  gl_Position = u_view_projection * world;
}
