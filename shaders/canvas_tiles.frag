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
// their point, in world space. PAPER_MARKS adds rice paper's fibres, spots and mottle in
// the second channel, as a change of brightness.
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
uniform float u_pin;              // 0: grain of fixed screen size; 1: it scales with the surface within an octave
uniform vec4 u_dome;              // world centre, radius
uniform vec3 u_eye;               // world
uniform uint u_seed;
uniform float u_tile_scale;       // tile values to unit variance
layout(location = 0) out vec2 o_canvas;  // grain (unit variance), marks (brightness change)

#include "noise_gabor.glsl"

// The Kuhn tetrahedron of the cubic lattice of spacing `spacing` (model units) holding P:
// corner 0 is the cube's lowest corner `c`, then c + i1, c + i2, c + 1 (i1: the axis of the
// largest fraction, i2: the largest two), with barycentric weights w. Selected
// arithmetically, without indexing by a variable (which a software rasteriser spills to
// memory).
struct Tetrahedron {
  ivec3 c, i1, i2;
  vec4 w;
};

Tetrahedron kuhn(vec3 P, float spacing) {
  vec3 q = P / spacing;
  vec3 base = floor(q), f = q - base;
  vec3 g = step(f.yzx, f.xyz), l = 1.0 - g;
  vec3 i1 = min(g, l.zxy), i2 = max(g, l.zxy);
  float hi = max(f.x, max(f.y, f.z)), lo = min(f.x, min(f.y, f.z)), mid = f.x + f.y + f.z - hi - lo;
  return Tetrahedron(ivec3(base), ivec3(i1), ivec3(i2), vec4(1.0 - hi, hi - mid, mid - lo, lo));
}

// A lattice point's hash: one multiply-xorshift round is enough to scatter neighbours.
uint cornerHash(uint level_seed, ivec3 c) {
  uint h = (level_seed ^ (uint(c.x) * 0x8DA6B343u) ^ (uint(c.y) * 0xD8163841u) ^ (uint(c.z) * 0xCB1AB31Fu)) * 0x9E3779B1u;
  return h ^ (h >> 15);
}

#ifdef PAPER_MARKS
// Rice paper's marks. Fibres and impurity spots hang on the grain's lattice points: a point
// carries a fibre (a thin curved thread of fixed screen size near the point's projection,
// in a random direction) or a spot with a small chance, and its marks fade out towards the
// edge of the lattice cells around it, so a fibre is at most about two lattice spacings
// long. The mottle is value noise on a coarser lattice (a random tone per point, mixed by
// the barycentric weights) on the background dome.
uniform vec4 u_fibre;          // chance per lattice point, mean half length (px), contrast, half width (px)
uniform vec3 u_spot;           // chance per lattice point, contrast, largest radius (px)
uniform vec2 u_mottle;         // contrast, lattice spacing on screen (pixels)

// Four bytes of a hash as numbers in [0, 1].
vec4 unitBytes(uint h) { return vec4(uvec4(h, h >> 8, h >> 16, h >> 24) & 0xFFu) * (1.0 / 255.0); }

// The fibre or spot of the lattice point hashed `h`, projected to `a`, at `pixel`. Without
// branches: a software rasteriser runs both sides of a branch, so the cheapest mark is one
// computed in full and multiplied by whether the point carries it.
float pointMarks(vec2 pixel, vec2 a, uint h) {
  uint h1 = noiseHash(h), h2 = noiseHash(h1), h3 = noiseHash(h2);
  vec2 chance = vec2(uvec2(h1 & 0xFFFFu, h1 >> 16)) * (1.0 / 65536.0);
  vec4 u = unitBytes(h2), v = unitBytes(h3);  // u: centre offset, direction; v: length, bend, width, sign
  vec2 q = pixel - a - (u.xy - 0.5) * u_fibre.y;
  vec2 along = normalize(u.zw - 0.5 + 1e-3);
  float half_length = u_fibre.y * (0.6 + 0.8 * v.x);
  float s = dot(q, along) / half_length;  // −1 … 1 along the fibre
  float across = (dot(q, vec2(-along.y, along.x)) - (v.y - 0.5) * 0.4 * half_length * (1.0 - s * s)) /
                 (u_fibre.w * (0.6 + 0.8 * v.z));
  float fibre = max(1.0 - across * across, 0.0) * (1.0 - smoothstep(0.5, 1.0, abs(s)));
  float radius = (0.2 + 0.8 * v.x * v.x) * u_spot.z;
  float spot = 1.0 - smoothstep(radius - 0.5, radius + 0.5, length(q));
  return step(chance.x, u_fibre.x) * (v.w < 0.75 ? -1.0 : 0.6) * u_fibre.z * fibre  // most darken, some lighten
         - step(chance.y, u_spot.x) * u_spot.y * spot;
}

// The mottle's tone at P from the lattice level `level` (spacing 2^level model units).
float mottleLevel(vec3 P, int level, int space) {
  Tetrahedron t = kuhn(P, exp2(float(level)));
  uint level_seed = noiseHash(u_seed + uint(space) * 0x2545F491u + uint(level + 512) * 0x7FEB352Du);
  vec4 v = vec4(cornerHash(level_seed, t.c), cornerHash(level_seed, t.c + t.i1), cornerHash(level_seed, t.c + t.i2),
                cornerHash(level_seed, t.c + 1)) * (2.0 / 4294967295.0) - 1.0;
  // Uniform values have variance 1/3: √3 over the weights' norm makes unit variance.
  return dot(t.w, v) * 1.7320508 * inversesqrt(dot(t.w, t.w));
}
#endif

// Adds one corner's tile copy: lattice point c, its clip coordinates, its weight (the
// level's `level_weight` times the barycentric `bary`); and, with marks, its fibre or spot
// to `marks`.
void addCorner(ivec3 c, vec4 clip, float level_weight, float bary, uint level_seed, vec2 pixel, float texels_per_pixel,
               inout float sum, inout float sum_w2, inout float marks) {
  if (clip.w <= 0.0) return;
  float w = level_weight * bary;
  vec2 a = (clip.xy / clip.w * 0.5 + 0.5) * u_viewport;
  uint h = cornerHash(level_seed, c);
  // The nearest texel (the tile has several texels per pixel, and wraps by a mask).
  ivec2 texel = ivec2(floor((pixel - a) * texels_per_pixel)) + ivec2(h & 0xFFFFu, h >> 16);
  sum += w * (imageLoad(u_tile, texel & u_tile_mask).r);
  sum_w2 += w * w;
#ifdef PAPER_MARKS
  // The level's share of the marks is its weight squared (cos² + sin² = 1).
  marks += level_weight * level_weight * smoothstep(0.0, 0.25, bary) * pointMarks(pixel, a, h);
#endif
}

// Adds the tile copies of lattice level `level` (spacing 2^level model units) at P, with
// weight `weight` in all. `offset` is P's continuous level minus `level` (in [−1, 1)): the
// copies' grain is read 2^(offset·pin) times finer, so with `pin` 1 it grows and shrinks
// with the surface between the level's octaves, as a texture pinned to it would.
void addLevel(vec3 P, int level, float offset, float weight, int space, mat4 to_clip, vec2 pixel, inout float sum,
              inout float sum_w2, inout float marks) {
  float spacing = exp2(float(level));
  float texels_per_pixel = u_texels_per_pixel * exp2(offset * u_pin);
  Tetrahedron t = kuhn(P, spacing);
  vec4 clip = to_clip * vec4(vec3(t.c) * spacing, 1.0);
  mat3x4 axes = mat3x4(to_clip[0], to_clip[1], to_clip[2]) * spacing;
  uint level_seed = noiseHash(u_seed + uint(space) * 0x68E31DA4u + uint(level + 512) * 0x1B56C4E9u);
  addCorner(t.c, clip, weight, t.w.x, level_seed, pixel, texels_per_pixel, sum, sum_w2, marks);
  addCorner(t.c + t.i1, clip + axes * vec3(t.i1), weight, t.w.y, level_seed, pixel, texels_per_pixel, sum, sum_w2, marks);
  addCorner(t.c + t.i2, clip + axes * vec3(t.i2), weight, t.w.z, level_seed, pixel, texels_per_pixel, sum, sum_w2, marks);
  addCorner(t.c + 1, clip + axes * vec3(1.0), weight, t.w.w, level_seed, pixel, texels_per_pixel, sum, sum_w2, marks);
}

// The view ray's exit through the dome around the scene (world space), and its clip w.
vec3 domePoint(vec2 ndc, out float w) {
  vec4 far = u_spaces[0].to_model * vec4(ndc, 1.0, 1.0);
  vec3 d = normalize(far.xyz / far.w - u_eye);
  vec3 o = u_eye - u_dome.xyz;
  float b = dot(o, d), c = dot(o, o) - u_dome.w * u_dome.w;
  vec3 P = u_eye + (-b + sqrt(max(b * b - c, 0.0))) * d;
  w = (u_spaces[0].to_clip * vec4(P, 1.0)).w;
  return P;
}

// Model units per pixel across the view at a point of clip w in `space`: one pixel further
// along x at the same w.
float modelPerPixel(int space, float w) {
  vec4 m1 = u_spaces[space].to_model * vec4(vec2(2.0 / u_viewport.x, 0.0) * w, 0.0, 0.0);
  return max(length(m1.xyz), 1e-30);
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
    P = domePoint(ndc, w);
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
  float model_per_pixel = modelPerPixel(space, w);
  float level = log2(u_patch_pixels * model_per_pixel);
  // The two lattices around P's level, weighted cos θ and sin θ with θ linear in the level:
  // the mix turns at a constant rate while the camera moves in or out, over a whole octave
  // (a narrower band turns faster and costs more warping error in a dolly than it saves).
  float lower = floor(level), theta = 1.5707963 * (level - lower);
  float sum = 0.0, sum_w2 = 0.0, marks = 0.0;
  mat4 to_clip = u_spaces[space].to_clip;
  addLevel(P, int(lower), level - lower, cos(theta), space, to_clip, pixel, sum, sum_w2, marks);
  addLevel(P, int(lower) + 1, level - lower - 1.0, sin(theta), space, to_clip, pixel, sum, sum_w2, marks);
  float grain = sum_w2 > 0.0 ? sum * inversesqrt(sum_w2) * u_tile_scale : 0.0;
#ifdef PAPER_MARKS
  if (u_mottle.x > 0.0) {
    // The mottle is the sheet's, behind everything: on the dome for every pixel, so that it
    // runs on across the edges of objects (pinned to each object's surface it would draw
    // their outlines, and a DEM's straight cut edges, as steps of tone). Two levels of its
    // lattice, mixed as the grain's (cos θ, sin θ keep unit variance).
    float dome_w;
    vec3 D = space == 0 ? P : domePoint(ndc, dome_w);
    float dome_per_pixel = space == 0 ? model_per_pixel : modelPerPixel(0, dome_w);
    float m_level = log2(u_mottle.y * dome_per_pixel), m_lower = floor(m_level), m_theta = 1.5707963 * (m_level - m_lower);
    marks += u_mottle.x * (cos(m_theta) * mottleLevel(D, int(m_lower), 0) + sin(m_theta) * mottleLevel(D, int(m_lower) + 1, 0));
  }
#endif
  o_canvas = vec2(grain, marks);
}
