// Ink of a pixel of the rendered picture, I = clamp(1 − lum / lum(paper), 0, 1): the
// extraction and the output both compute it from the colour, so the output's "before" is
// the extraction's value to the bit and an untouched pixel keeps its colour exactly.
float inkOf(vec3 colour, vec3 paper) {
  const vec3 weights = vec3(0.2126, 0.7152, 0.0722);
  // precise: the same operations in both shaders, whatever each compiler would fuse.
  precise float ink = clamp(1.0 - dot(colour, weights) / max(dot(paper, weights), 1e-6), 0.0, 1.0);
  return ink;
}
