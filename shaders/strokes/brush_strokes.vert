#version 450 core
// Brush strokes (seed 002): the strip each stroke sweeps, in pixels (strokes/brush.h).
layout(location = 0) in vec2 a_position;  // pixels, GL's origin (bottom left)
layout(location = 1) in vec4 a_stroke;    // along (pixels), across (-1 right, +1 left), pressure, presence
layout(location = 2) in vec3 a_colour;    // the object's line colour
uniform vec2 u_size;
out vec4 v_stroke;
out vec3 v_colour;
void main() {
  v_stroke = a_stroke;
  v_colour = a_colour;
  gl_Position = vec4(a_position / u_size * 2.0 - 1.0, 0.0, 1.0);
}
