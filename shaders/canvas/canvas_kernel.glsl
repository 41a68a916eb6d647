// The canvas noise kernel, the GLSL twin of libs/noise canvasKernel(): silk (CANVAS_SILK) is
// a Gabor kernel mixed with its twin across it (the weft), rice paper a Gaussian window over
// Perlin noise at a per-impulse offset. Needs noise_gabor.glsl (and noise_perlin.glsl for
// rice paper) included first.
uniform vec4 u_kernel;       // radius r, bandwidth a, F0, ω0
uniform vec4 u_kernel_misc;  // silk mix, Perlin cycles per unit length, isotropic (0/1), 1 / σ

float canvasKernel(vec2 d, vec3 e) {
  float r = u_kernel.x, a = u_kernel.y;
  float d2 = dot(d, d);
  if (d2 >= r * r) return 0.0;
#ifdef CANVAS_SILK
  float omega = u_kernel_misc.z > 0.5 ? 2.0 * kNoisePi * e.x : u_kernel.w;
  float m = u_kernel_misc.x;
  // The twin at swapped coordinates with −ω runs at ω + 90°: the weft across the warp.
  return (1.0 - m) * gaborKernel(d, 1.0, a, u_kernel.z, omega) + m * gaborKernel(d.yx, 1.0, a, u_kernel.z, -omega);
#else
  return exp(-kNoisePi * a * a * d2) * perlin(vec3(d * u_kernel_misc.y + 256.0 * e.xy, 256.0 * e.z));
#endif
}
