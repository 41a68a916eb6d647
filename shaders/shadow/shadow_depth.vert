#version 450 core
// The shadow map: every object's depth seen from the light (orthographic).
layout(location = 0) in vec3 a_position;
uniform mat4 u_light_model_view_projection;
void main() {
  gl_Position = u_light_model_view_projection * vec4(a_position, 1.0);
}
