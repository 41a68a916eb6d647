// Kubelka–Munk (libs/pigment/kubelka_munk.h, the reference this is tested against): a
// layer of a pigment, given by its per-channel S, a and b, `thickness` unit layers thick,
// lying on a ground of reflectance `ground`. Written with e^(-x) so nothing overflows.
vec3 kmOnGround(vec3 S, vec3 a, vec3 b, float thickness, vec3 ground) {
  vec3 x = b * S * thickness;
  vec3 e1 = exp(-x);
  vec3 e2 = e1 * e1;
  vec3 d = a * (1.0 - e2) + b * (1.0 + e2);
  vec3 R = (1.0 - e2) / d;
  vec3 T = 2.0 * b * e1 / d;
  return R + T * T * ground / (1.0 - R * ground);
}
