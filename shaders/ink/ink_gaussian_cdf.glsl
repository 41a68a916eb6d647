// Φ(x), the standard normal CDF, for the smoothed steps of the shading. GLSL has no erf:
// Abramowitz & Stegun 7.1.26, |error| < 1.5e-7 in erf (bench/ink_tradeoff.cpp compares it
// with std::erf and with the cheaper logistic approximation).
float gaussianCdf(float x) {
  float z = abs(x) * 0.70710678;
  float t = 1.0 / (1.0 + 0.3275911 * z);
  float poly = t * (0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429))));
  float erf_z = 1.0 - poly * exp(-z * z);
  return 0.5 + 0.5 * sign(x) * erf_z;
}
