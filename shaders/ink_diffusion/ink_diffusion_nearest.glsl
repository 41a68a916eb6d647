// Ink diffusion, main region: the nearest stroke pixel that the distance transform's sweeps
// carry, as one unsigned key: the city-block distance in the top 9 bits, the stroke's ink
// below them, inverted and quantised to 23 bits. The smaller key is the nearer stroke and,
// between strokes as near, the one with more ink (the reference's tie rule), so a step of
// a sweep is one comparison and one image access where a distance and an ink took two. The
// quantisation moves the ink by less than 3e-7.
const uint kInkBits = 23u;
const uint kInkMax = (1u << kInkBits) - 1u;
const uint kFar = 0xFFFFFFFFu;  // no stroke within d (ring_steps ≤ 256 < 511)

// A stroke pixel itself: distance 0.
uint strokeKey(float ink) { return kInkMax - uint(round(clamp(ink, 0.0, 1.0) * float(kInkMax))); }
uint keyDistance(uint key) { return key >> kInkBits; }
float keyInk(uint key) { return float(kInkMax - (key & kInkMax)) / float(kInkMax); }

// The same stroke seen from one pixel further: its distance + 1, or far beyond d.
uint further(uint key, int ring_steps) {
  if (key == kFar) return kFar;
  key += 1u << kInkBits;
  return keyDistance(key) > uint(ring_steps) ? kFar : key;
}
