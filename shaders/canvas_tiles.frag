#version 450 core
// The `tiles` canvas: one full-screen pass that pins copies of a precomputed noise tile
// (canvas_static.frag with CANVAS_TILE: the splatted canvas's kernels, wrapped) to the
// surfaces. Each pixel's surface point P, in its object's model space, lies in a tetrahedron
// of a cubic lattice whose spacing is `patch` kernel radii of screen at P's distance; each of
// the tetrahedron's four corners projects to a screen point a, and the tile is read at
// (pixel − a) in pixels from a random offset of that corner. The four reads are mixed with
// the barycentric weights w and divided by √Σw² (the variance-preserving blend of Heitz and
// Neyret 2018): grain of fixed screen size and orientation, moving with the corners on the
// surface. The lattice spacing doubles with distance: the two octaves around P's are
// blended. Each corner's copy is read at the nearest texel (the tile has several texels per
// pixel). Background pixels take the view ray's exit through the dome around the scene as
// their point, in world space.
layout(binding = 0) uniform sampler2D u_depth;    // the G-buffer's
layout(binding = 1) uniform sampler2D u_surface;  // a: object id (index + 1) / 255
// Zero mean, a power of two on a side, wrapped by a mask. An image: reading a texel costs a
// software rasteriser less than a texture's texelFetch (no sampler state).
layout(binding = 0, r8_snorm) readonly uniform image2D u_tile;

struct Space {
  mat4 to_model;  // clip coordinates → the object's model space (the dome's: world)
  mat4 to_clip;   // model space → clip coordinates
};
layout(std140, binding = 0) uniform Spaces { Space u_spaces[SPACES]; };  // [0]: background

uniform vec2 u_viewport;          // pixels
uniform float u_texels_per_pixel;
uniform int u_tile_mask;           // tile size − 1 (a power of two)
uniform float u_patch_pixels;     // lattice spacing on screen: patch × r, pixels
uniform vec4 u_dome;              // world centre, radius
uniform vec3 u_eye;               // world
uniform uint u_seed;
uniform float u_tile_scale;       // tile values to unit variance
layout(location = 0) out float o_canvas;

#include "noise_gabor.glsl"

// Adds one corner's tile copy: lattice point c (integer), its clip coordinates, weight w.
void addCorner(ivec3 c, vec4 clip, float w, uint level_seed, vec2 pixel, inout float sum,
               inout float sum_w2) {
  if (clip.w <= 0.0) return;
  vec2 a = (clip.xy / clip.w * 0.5 + 0.5) * u_viewport;
  // One multiply-xorshift round is enough to scatter neighbouring corners over the tile.
  uint h = (level_seed ^ (uint(c.x) * 0x8DA6B343u) ^ (uint(c.y) * 0xD8163841u) ^ (uint(c.z) * 0xCB1AB31Fu)) * 0x9E3779B1u;
  h ^= h >> 15;
  // The nearest texel (the tile has several texels per pixel, and wraps by a mask).
  ivec2 texel = ivec2(floor((pixel - a) * u_texels_per_pixel)) + ivec2(h & 0xFFFFu, h >> 16);
  sum += w * (imageLoad(u_tile, texel & u_tile_mask).r);
  sum_w2 += w * w;
}

// Adds the tile copies of lattice level `level` (spacing 2^level model units) at P, with
// weight `weight` in all.
void addLevel(vec3 P, int level, float weight, int space, mat4 to_clip, vec2 pixel,
              inout float sum, inout float sum_w2) {
  float spacing = exp2(float(level));
  vec3 q = P / spacing;
  vec3 base = floor(q), f = q - base;
  // The Kuhn tetrahedron holding f: from the cube's corner along the axes in order of
  // decreasing f (i1: the largest axis, i2: the largest two); the barycentric weights are
  // the differences of the sorted f. Selected arithmetically, without indexing by a
  // variable (which a software rasteriser spills to memory).
  vec3 g = step(f.yzx, f.xyz), l = 1.0 - g;
  vec3 i1 = min(g, l.zxy), i2 = max(g, l.zxy);
  float hi = max(f.x, max(f.y, f.z)), lo = min(f.x, min(f.y, f.z)), mid = f.x + f.y + f.z - hi - lo;
  vec4 clip = to_clip * vec4(base * spacing, 1.0);
  mat3x4 axes = mat3x4(to_clip[0], to_clip[1], to_clip[2]) * spacing;
  ivec3 c = ivec3(base);
  uint level_seed = noiseHash(u_seed + uint(space) * 0x68E31DA4u + uint(level + 512) * 0x1B56C4E9u);
  addCorner(c, clip, weight * (1.0 - hi), level_seed, pixel, sum, sum_w2);
  addCorner(c + ivec3(i1), clip + axes * i1, weight * (hi - mid), level_seed, pixel, sum, sum_w2);
  addCorner(c + ivec3(i2), clip + axes * i2, weight * (mid - lo), level_seed, pixel, sum, sum_w2);
  addCorner(c + 1, clip + axes * vec3(1.0), weight * lo, level_seed, pixel, sum, sum_w2);
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 pixel = gl_FragCoord.xy;
  vec2 ndc = pixel / u_viewport * 2.0 - 1.0;
  float depth = texelFetch(u_depth, p, 0).r;
  int space = 0;
  vec3 P;
  float w;  // clip w: the distance along the view axis
  if (depth >= 1.0) {
    vec4 far = u_spaces[0].to_model * vec4(ndc, 1.0, 1.0);
    vec3 d = normalize(far.xyz / far.w - u_eye);
    vec3 o = u_eye - u_dome.xyz;
    float b = dot(o, d), c = dot(o, o) - u_dome.w * u_dome.w;
    P = u_eye + (-b + sqrt(max(b * b - c, 0.0))) * d;
    w = (u_spaces[0].to_clip * vec4(P, 1.0)).w;
  } else {
#ifdef SINGLE_OBJECT
    space = 1;
#else
    space = int(texelFetch(u_surface, p, 0).a * 255.0 + 0.5);
#endif
    vec4 m = u_spaces[space].to_model * vec4(ndc, depth * 2.0 - 1.0, 1.0);
    P = m.xyz / m.w;
    w = 1.0 / m.w;
  }
  // Model units per pixel at P, across the view: one pixel further along x at the same w.
  vec4 m1 = u_spaces[space].to_model * vec4(vec2(2.0 / u_viewport.x, 0.0) * w, 0.0, 0.0);
  float model_per_pixel = max(length(m1.xyz), 1e-30);
  float level = log2(u_patch_pixels * model_per_pixel);
  // The two lattices around P's level, weighted cos θ and sin θ with θ linear in the level:
  // the mix turns at a constant rate while the camera moves in or out, over a whole octave
  // (a narrower band turns faster and costs more warping error in a dolly than it saves).
  float lower = floor(level), theta = 1.5707963 * (level - lower);
  float sum = 0.0, sum_w2 = 0.0;
  mat4 to_clip = u_spaces[space].to_clip;
  addLevel(P, int(lower), cos(theta), space, to_clip, pixel, sum, sum_w2);
  addLevel(P, int(lower) + 1, sin(theta), space, to_clip, pixel, sum, sum_w2);
  o_canvas = sum_w2 > 0.0 ? sum * inversesqrt(sum_w2) * u_tile_scale : 0.0;
}
