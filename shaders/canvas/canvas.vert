#version 450 core
// Dynamic canvas (seed 001 Eqs. 12-17): triangles pass through to canvas.geom, which
// scatters the noise kernels on them.
layout(location = 0) in vec3 a_position;
uniform mat4 u_model_view_projection;
out vec3 v_model;  // model space: the triangle's seed comes from it

void main() {
  v_model = a_position;
  gl_Position = u_model_view_projection * vec4(a_position, 1.0);
}
