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

// Value noise over the cell whose low corner is c, at f in [0, 1)² (already eased): its four
// corners' hashes (salted along x by `salt`, 0 for none) blended bilinearly, in [0, 1).
float cellValue(uvec2 c, vec2 f, uint salt) {
  uvec2 s = uvec2(salt, 0u);
  vec4 h = vec4(cellHash(c ^ s), cellHash((c + uvec2(1u, 0u)) ^ s), cellHash((c + uvec2(0u, 1u)) ^ s),
                cellHash((c + uvec2(1u, 1u)) ^ s)) /
           4294967296.0;
  return mix(mix(h.x, h.y, f.x), mix(h.z, h.w, f.x), f.y);
}
#endif
