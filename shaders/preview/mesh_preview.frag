#version 450 core
// Preview shading: three ink tones from the diffuse term with smoothed steps, and a dark
// rim where the surface turns away from the viewer. The full ink-wash passes replace it.
in vec3 v_normal;
in vec3 v_to_eye;

uniform vec3 u_light_dir;   // unit vector towards the light
uniform vec3 u_paper;       // paper colour
uniform vec3 u_ink;         // darkest ink colour
uniform float u_rim_width;  // N.V below which the rim starts to darken, [0, 1]
#ifdef CHECKER
in vec2 v_uv;
uniform float u_checker_squares;  // squares per UV unit
#endif

out vec4 o_colour;

float step_soft(float edge, float x) { return smoothstep(edge - 0.04, edge + 0.04, x); }

void main() {
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  float diffuse = max(dot(n, u_light_dir), 0.0);
  float lightness = 0.30 + 0.35 * step_soft(0.35, diffuse) + 0.30 * step_soft(0.7, diffuse);
  float n_dot_v = abs(dot(n, normalize(v_to_eye)));
  float rim = smoothstep(0.5 * u_rim_width, u_rim_width, n_dot_v);
#ifdef CHECKER
  // Checkerboard over the shading: stretch and folds in the UVs show as distorted squares.
  vec2 cell = floor(v_uv * u_checker_squares);
  lightness *= mod(cell.x + cell.y, 2.0) < 1.0 ? 0.55 : 1.0;
#endif
  o_colour = vec4(mix(u_ink, u_paper, lightness * mix(0.15, 1.0, rim)), 1.0);
}
