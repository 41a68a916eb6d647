#version 450 core
// Ink of a brush stroke: the bristle footprint is elliptic (ink falls off towards the
// stroke's edges) and the bristles leave dry streaks along the stroke where the brush
// presses lightly, as a dry brush lifting off the paper does.
// The atmosphere and the dissolving border take the stroke back to the paper as they do the
// surface under it (its ink times that presence, per point from the CPU).
in vec4 v_stroke;  // along (pixels), across (-1..1), pressure, ink
in vec3 v_colour;  // the object's line colour
uniform float u_bristle_px;  // bristle streak length, pixels
out vec4 frag;

float hash(vec2 p) {
  return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453);
}

void main() {
  float across = clamp(v_stroke.y, -1.0, 1.0);
  float footprint = sqrt(max(0.0, 1.0 - across * across));
  float bristle = hash(vec2(floor((across * 0.5 + 0.5) * 10.0), floor(v_stroke.x / u_bristle_px)));
  // Dry where the pressure is low and the bristle is thin: up to 60 % less ink.
  float dry = clamp((1.0 - v_stroke.z) * 1.4 - 0.4, 0.0, 1.0) * bristle;
  float a = v_stroke.w * (0.45 + 0.55 * footprint) * (1.0 - 0.6 * dry);
  frag = vec4(v_colour, a);
}
