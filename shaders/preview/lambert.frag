#version 450 core
in vec3 v_normal;
uniform vec3 u_light_dir;
out vec4 o_colour;
void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  o_colour = vec4(vec3(max(dot(n, u_light_dir), 0.0)), 1.0);
}
