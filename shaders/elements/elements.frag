#version 450 core
// One brush mark of an element (libs/elements/brushwork.h's shapes): its ink where the
// brush covers the pixel, with a broken edge (dabs) or a bristle's streaks (strokes), and
// with NEARNESS (animated scenes) the nearness of the mark, 1 − depth; the pass keeps the
// largest of each (GL_MAX).
in vec2 v_local;
flat in float v_length;
flat in float v_ink;
flat in int v_shape;
flat in float v_seed;
flat in float v_pixel;
flat in vec2 v_turn;  // cosine and sine of the dab's turn, from the seed
#ifdef NEARNESS
layout(location = 0) out vec2 o_ink;  // ink, nearness
#else
layout(location = 0) out float o_ink;
#endif

float hash(vec2 p) {
  return fract(sin(dot(p, vec2(127.1, 311.7))) * 43758.5453);
}

const int kDab = 0, kLeaf = 1, kBranch = 2;

void main() {
  float s = v_local.x, t = v_local.y, len = v_length;
  float d;  // below 1 inside the mark
  if (v_shape == kDab) {
    // A round-ended blot whose radius wobbles with the direction: three and two lobes, turned
    // by the seed (polynomials of the direction's cosine and sine, no trigonometry).
    vec2 q = vec2(s - clamp(s, 0.0, len), t);
    float r = length(q);
    vec2 n = r > 0.0 ? q / r : vec2(1.0, 0.0);
    float sin3 = n.y * (3.0 - 4.0 * n.y * n.y), cos3 = n.x * (4.0 * n.x * n.x - 3.0);
    float sin2 = 2.0 * n.x * n.y, cos2 = n.x * n.x - n.y * n.y;
    d = r * (1.0 + 0.13 * (sin3 * v_turn.x + cos3 * v_turn.y) + 0.07 * (sin2 * v_turn.y + cos2 * v_turn.x));
  } else if (v_shape == kLeaf) {
    // Pointed at both ends: the half width √(4u(1 − u)) along it.
    float u = len > 0.0 ? s / len : 0.5;
    float half_width = sqrt(max(4.0 * u * (1.0 - u), 0.0));
    d = (s < 0.0 || s > len) ? 2.0 : abs(t) / max(half_width, 1e-3);
  } else {
    float u = len > 0.0 ? clamp(s / len, 0.0, 1.0) : 0.5;
    float half_width = mix(1.0, 0.55, u);
    d = s < 0.0 ? length(vec2(s, t)) : (s > len ? length(vec2(s - len, t)) / 0.55 : abs(t) / half_width);
  }
  float cover = 1.0 - smoothstep(1.0 - v_pixel, 1.0 + v_pixel, d);
  // Bristles: the ink varies across the stroke in a few streaks along it.
  float streak = hash(vec2(floor((t * 0.5 + 0.5) * 5.0), floor(v_seed * 4096.0)));
  float ink = v_ink * cover * (0.8 + 0.2 * streak);
  if (ink <= 0.0) discard;
#ifdef NEARNESS
  o_ink = vec2(ink, 1.0 - gl_FragCoord.z);
#else
  o_ink = ink;
#endif
}
