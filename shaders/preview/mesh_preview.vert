#version 450 core
// Preview pass: positions relative to the mesh centre, normals in model space.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#ifdef CHECKER
layout(location = 2) in vec2 a_uv;
out vec2 v_uv;
#endif

uniform mat4 u_view_projection;
uniform vec3 u_eye;  // camera position in the same space as a_position

out vec3 v_normal;
out vec3 v_to_eye;

void main() {
  v_normal = a_normal;
  v_to_eye = u_eye - a_position;
#ifdef CHECKER
  v_uv = a_uv;
#endif
  gl_Position = u_view_projection * vec4(a_position, 1.0);
}
