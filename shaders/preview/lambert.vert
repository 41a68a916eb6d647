#version 450 core
// Plain Lambert render, the baseline the ink passes are measured against (bench/).
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_model;
uniform mat3 u_normal_matrix;
uniform mat4 u_view_projection;
out vec3 v_normal;
void main() {
  v_normal = u_normal_matrix * a_normal;
  gl_Position = u_view_projection * (u_model * vec4(a_position, 1.0));
}
