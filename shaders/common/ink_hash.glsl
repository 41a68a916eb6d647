// An integer hash of a grid cell, for marks placed per cell (slope wrinkles, wave strokes).
#ifndef INK_HASH_GLSL
#define INK_HASH_GLSL
uint cellHash(uvec2 p) {
  uint h = p.x * 0x8da6b343u ^ p.y * 0xd8163841u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  return h;
}
#endif
