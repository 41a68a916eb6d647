// The `tiles` canvas's lattices and spaces, shared by its vertex and fragment shaders
// (canvas_tiles.frag, canvas_mottle.frag).
#include "noise_gabor.glsl"

struct Space {
  mat4 to_model;  // clip coordinates → the object's model space (the dome's: world)
  mat4 to_clip;   // model space → clip coordinates
  vec4 pixel;     // x: model units across a pixel at clip w 1
};
layout(std140, binding = 0) uniform Spaces { Space u_spaces[SPACES]; };  // [0]: background

uniform vec2 u_viewport;  // pixels
uniform vec4 u_dome;      // world centre, radius
uniform vec3 u_eye;       // world
uniform uint u_seed;

// The Kuhn tetrahedron of the cubic lattice of unit spacing holding q (a point in units of
// the lattice's spacing): corner 0 is the cube's lowest corner `c`, then c + i1, c + i2,
// c + 1 (i1: the axis of the largest fraction, i2: the largest two), with barycentric
// weights w; f is q's place in the cube (0 … 1 on each axis). Selected arithmetically,
// without indexing by a variable (which a software rasteriser spills to memory).
struct Tetrahedron {
  ivec3 c;
  vec3 i1, i2, f;
  vec4 w;
};

Tetrahedron kuhnScaled(vec3 q) {
  vec3 base = floor(q), f = q - base;
  vec3 g = step(f.yzx, f.xyz), l = 1.0 - g;
  vec3 i1 = min(g, l.zxy), i2 = max(g, l.zxy);
  float hi = max(f.x, max(f.y, f.z)), lo = min(f.x, min(f.y, f.z)), mid = f.x + f.y + f.z - hi - lo;
  return Tetrahedron(ivec3(base), i1, i2, f, vec4(1.0 - hi, hi - mid, mid - lo, lo));
}

// The same for P in the lattice of spacing 2^level (model units).
Tetrahedron kuhn(vec3 P, int level) { return kuhnScaled(P * ldexp(1.0, -level)); }

// A lattice point's hash, one multiply-xorshift round, in two steps: the coordinates'
// products (a corner's are its cube's plus the multipliers of the axes it steps along, so
// four corners cost one set of multiplies) and the mix with the level's seed.
const uvec3 kCornerMultipliers = uvec3(0x8DA6B343u, 0xD8163841u, 0xCB1AB31Fu);
uvec3 cornerProducts(ivec3 c) { return uvec3(c) * kCornerMultipliers; }
uvec3 stepProducts(uvec3 products, vec3 step01) { return products + (kCornerMultipliers & uvec3(-ivec3(step01))); }
uint cornerHash(uint level_seed, uvec3 products) {
  uint h = (level_seed ^ products.x ^ products.y ^ products.z) * 0x9E3779B1u;
  return h ^ (h >> 15);
}

// The view ray's exit through the dome around the scene (world space), and its clip w. The
// ray is eye + s D with D = far.w (far − eye), far the ray's point on the far plane (far.w
// > 0: its length does not matter), and s the larger root of |eye + s D − centre|² = r²:
// one square root and one division (a software rasteriser pays for each).
vec3 domePoint(vec2 ndc, out float w) {
  vec4 far = u_spaces[0].to_model * vec4(ndc, 1.0, 1.0);
  vec3 D = far.xyz - u_eye * far.w, o = u_eye - u_dome.xyz;
  float a = dot(D, D), b = dot(o, D), c = dot(o, o) - u_dome.w * u_dome.w;
  vec3 P = u_eye + ((sqrt(max(b * b - a * c, 0.0)) - b) / a) * D;
  w = (u_spaces[0].to_clip * vec4(P, 1.0)).w;
  return P;
}

// Model units per pixel across the view at a point of clip w in `space`: one pixel further
// along x at the same w is a clip offset of (2w / width, 0, 0, 0), which to_model takes to
// that multiple of its first column (Space.pixel, computed with the matrices).
float modelPerPixel(int space, float w) { return max(u_spaces[space].pixel.x * w, 1e-30); }

#ifdef MOTTLE
// Rice paper's mottle: value noise (a random tone per lattice point, mixed by the
// barycentric weights) on the background dome, two levels of a lattice u_mottle.y pixels
// apart on screen mixed as the grain's. It is the sheet's, behind everything: on the dome
// for every pixel, so that it runs on across the edges of objects (pinned to each object's
// surface it would draw their outlines, and a DEM's straight cut edges, as steps of tone).
uniform vec2 u_mottle;  // contrast, lattice spacing on screen (pixels)

float mottleLevel(vec3 P, int level) {
  Tetrahedron t = kuhn(P, level);
  uint level_seed = noiseHash(u_seed + uint(level + 512) * 0x7FEB352Du);
  uvec3 products = cornerProducts(t.c);
  vec4 v = vec4(cornerHash(level_seed, products), cornerHash(level_seed, stepProducts(products, t.i1)),
                cornerHash(level_seed, stepProducts(products, t.i2)), cornerHash(level_seed, products + kCornerMultipliers)) *
               (2.0 / 4294967295.0) -
           1.0;
  // Uniform values have variance 1/3: √3 over the weights' norm makes unit variance.
  return dot(t.w, v) * 1.7320508 * inversesqrt(dot(t.w, t.w));
}

// The mottle's brightness change at the dome's point D of clip w.
float mottleAt(vec3 D, float w) {
  float level = log2(u_mottle.y * modelPerPixel(0, w)), lower = floor(level), theta = 1.5707963 * (level - lower);
  return u_mottle.x * (cos(theta) * mottleLevel(D, int(lower)) + sin(theta) * mottleLevel(D, int(lower) + 1));
}
#endif
