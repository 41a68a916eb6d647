// Sparse-convolution Gabor noise in float: the GLSL twin of libs/noise GaborNoise (the
// same 32-bit hashes, impulse counts, positions, weights and orientations, drawn in the
// same order), and the random streams the canvas pass shares with it.
const float kNoisePi = 3.14159265358979;

uint noiseHash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
uint noiseCellSeed(ivec2 cell, uint seed) { return noiseHash(noiseHash(seed + uint(cell.x)) + uint(cell.y)); }
uint noiseStream(uint s, uint k) { return noiseHash(s + 0x9E3779B9u * k); }
// Top 24 bits: exact in float, as on the CPU in double.
float noiseUnit(uint v) { return float(v >> 8) * (1.0 / 16777216.0); }
int impulseCount(float mean, float u) {
  float whole = floor(mean);
  return int(whole) + (u < mean - whole ? 1 : 0);
}

// One kernel, K e^(−π a² |d|²) cos(2π F0 (d_x cos ω + d_y sin ω)).
float gaborKernel(vec2 d, float K, float a, float F0, float omega) {
  return K * exp(-kNoisePi * a * a * dot(d, d)) * cos(2.0 * kNoisePi * F0 * (d.x * cos(omega) + d.y * sin(omega)));
}

struct GaborParams {
  float K, a, F0, omega0;
  bool isotropic;
  float impulses;  // N′
  uint seed;       // noiseSeed32 of the 64-bit seed
};

float gaborRadius(GaborParams g) { return sqrt(-log(0.05) / kNoisePi) / g.a; }

float gaborNoise(vec2 p, GaborParams g) {
  float r = gaborRadius(g);
  float mean = g.impulses / kNoisePi;  // λ r² with λ = N′ / (π r²)
  vec2 c = floor(p / r);
  float sum = 0.0;
  for (int dj = -1; dj <= 1; ++dj) {
    for (int di = -1; di <= 1; ++di) {
      ivec2 cell = ivec2(c) + ivec2(di, dj);
      uint s = noiseCellSeed(cell, g.seed);
      uint k = 0u;
      int count = impulseCount(mean, noiseUnit(noiseStream(s, k++)));
      for (int n = 0; n < count; ++n) {
        float px = (float(cell.x) + noiseUnit(noiseStream(s, k++))) * r;
        float py = (float(cell.y) + noiseUnit(noiseStream(s, k++))) * r;
        float w = 2.0 * noiseUnit(noiseStream(s, k++)) - 1.0;
        float omega = g.omega0;
        if (g.isotropic) omega = 2.0 * kNoisePi * noiseUnit(noiseStream(s, k++));
        vec2 d = p - vec2(px, py);
        if (dot(d, d) >= r * r) continue;
        sum += w * gaborKernel(d, g.K, g.a, g.F0, omega);
      }
    }
  }
  return sum;
}
