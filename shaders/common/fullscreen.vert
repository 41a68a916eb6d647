#version 450 core
// One triangle covering the viewport; the image passes read their inputs with texelFetch.
// It lies on the far plane (depth 1, the G-buffer's background), so a pass with the
// G-buffer's depth attached can keep to the surfaces (GL_GREATER) or the background
// (GL_EQUAL) by the depth test, which skips the other pixels before they are shaded.
void main() {
  vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 1.0, 1.0);
}
