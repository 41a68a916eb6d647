#version 450 core
// The `tiles` canvas: a full-screen pass that pins copies of a precomputed noise tile
// (canvas_static.frag with CANVAS_TILE: the splatted canvas's kernels, wrapped) to the
// surfaces. Each pixel's surface point P, in its object's model space, lies in a tetrahedron
// of a cubic lattice whose spacing is `patch` kernel radii of screen at P's distance; each of
// the tetrahedron's corners projects to a screen point a, and the tile is read at
// (pixel − a) in pixels from a random offset of that corner. The reads are mixed with the
// barycentric weights w less the smallest of them, so the corner of least weight drops out
// (its weight reaches 0 exactly where another takes its place: three reads instead of four,
// ~1 ms of ~20 at 1024x768), and divided by √Σw² (the variance-preserving blend of Heitz and
// Neyret 2018): grain of fixed screen size and orientation, moving with the corners on the
// surface. The lattice spacing doubles with distance: the two octaves around P's are
// blended. Each corner's copy is read at the nearest texel (the tile has several texels per
// pixel).
//
// Two programs draw it, kept apart by the depth test against a copy of the G-buffer's depth
// (fullscreen.vert's triangle lies on the far plane): the surfaces' (GL_GREATER) and, with
// BACKGROUND, the background's (GL_EQUAL), whose point is the view ray's exit through the
// dome around the scene, in world space. A software rasteriser runs both sides of a branch
// for every pixel; the depth test skips the other program's pixels before they are shaded.
// PAPER_MARKS adds rice paper's fibres and spots in the second channel as a change of
// brightness, MOTTLE its mottle (canvas_mottle.frag's image); GRAIN_ON_SURFACE lets the grain
// grow and shrink with the surface between octaves. With PIXEL_COMPUTE it is a compute
// shader instead (pixel_main.glsl), each program testing the depth itself.
#include "pixel_stage.glsl"
#ifndef PIXEL_COMPUTE
layout(early_fragment_tests) in;
#endif
#include "canvas_lattice.glsl"

#ifndef BACKGROUND
layout(binding = 0) uniform sampler2D u_depth;    // the G-buffer's
layout(binding = 1) uniform sampler2D u_surface;  // a: object id (index + 1) / 255
#endif
// Zero mean, a power of two on a side, wrapped by a mask; signed bytes (× u_tile_scale), rows
// from the bottom, read by index. An image: reading a texel costs a software rasteriser less
// than a texture's texelFetch (no sampler state), and a buffer's less than a 2D image's.
layout(binding = 0, r8i) readonly uniform iimageBuffer u_tile;
uniform int u_tile_shift;       // log2 of the tile's size
uniform vec2 u_ndc_per_pixel;  // 2 / the viewport's size
uniform float u_texels_per_pixel;
uniform int u_tile_mask;        // tile size − 1 (a power of two)
uniform float u_patch_pixels;  // lattice spacing on screen: patch × r, pixels
uniform float u_tile_scale;    // tile bytes to unit variance
#ifdef MOTTLE
layout(binding = 1, r32f) readonly uniform image2D u_mottle_image;  // canvas_mottle.frag's
uniform float u_mottle_texels;                                      // texels per pixel of the view
#endif
#ifdef PIXEL_COMPUTE
layout(binding = 2, rg16f) writeonly uniform image2D u_canvas_out;
vec2 o_canvas;
void pixelOutputsClear() { o_canvas = vec2(0.0); }
void pixelStore(ivec2 p) { imageStore(u_canvas_out, p, vec4(o_canvas, 0.0, 0.0)); }
#else
layout(location = 0) out vec2 o_canvas;  // grain (unit variance), marks (brightness change)
#endif

#ifdef PAPER_MARKS
// Rice paper's fibres and impurity spots hang on lattice points: a point carries a fibre (a
// thin curved thread of fixed screen size near the point's projection, in a random
// direction) or a spot with a small chance, and shows it over its cube of the lattice (where
// P is nearer to it than to any other point). The marks' lattice is a coarser level than the grain's, 2.8 to
// 5.7 grain spacings on screen, so that a fibre fits its cube; it steps up by one level
// halfway through the grain's octave, where the marks fade out and in over a twentieth of
// an octave (a pixel shows one point's marks: the grain's eight corners' cost a third of
// the pass). A point's chance grows with its cube's area on screen, so that the marks per
// pixel stay put as the camera moves in or out.
uniform vec2 u_mark_chance;    // a fibre's and a spot's, per grain spacing² of screen
uniform vec2 u_mark_contrast;  // a fibre's and a spot's

// The shapes: u_mark_variants sprites of u_mark_sprite² texels (powers of two), u_mark_texels
// a pixel, centred on the lattice point's projection; a texel holds a fibre (signed: most
// darken, some lighten) and a spot, as bytes of 1 / 127 (CanvasPass::markSprite draws
// them).
layout(binding = 3, rg8i) readonly uniform iimageBuffer u_marks;
uniform float u_mark_texels;
uniform int u_mark_sprite, u_mark_variants;

// The fibre or spot of the lattice point hashed `h` at `d`, the pixel's offset from the
// point's projection (pixels); the screen area the point's marks cover is area / m2 grain
// spacings² (compared without dividing). Whether the point carries a fibre or a spot comes
// from the halves of h (which also place the point's tile copy: harmless), its shape from
// one more multiply-xorshift round. One read of a sprite instead of the shape's arithmetic
// (~0.8 ms of ~19 at 1024x768): the read is out of range, so it returns 0 without touching
// memory, where the point carries nothing or the pixel is beyond the sprite.
float pointMarks(vec2 d, uint h, float area, float m2) {
  vec2 chance = vec2(uvec2(h >> 16, h & 0xFFFFu)) * (1.0 / 65536.0);
  vec2 carries = step(chance * m2, u_mark_chance * area);
  uint h2 = (h ^ (h >> 16)) * 0x7FEB352Du;
  h2 ^= h2 >> 15;
  ivec2 texel = ivec2(floor(d * u_mark_texels)) + u_mark_sprite / 2;
  bool read = carries.x + carries.y > 0.0 && all(lessThan(uvec2(texel), uvec2(u_mark_sprite)));
  int index = read ? ((int(h2) & (u_mark_variants - 1)) * u_mark_sprite + texel.y) * u_mark_sprite + texel.x : -1;
  vec2 shape = vec2(imageLoad(u_marks, index).rg) * (1.0 / 127.0);
  return carries.x * u_mark_contrast.x * shape.x - carries.y * u_mark_contrast.y * shape.y;
}
#endif

// The running sums of a pixel: the grain's weighted reads and their squared weights.
struct Sums {
  float grain, w2;
};

// Adds one corner's tile copy: `d` is the pixel's offset from the corner's projection
// (pixels), `products` its hash products, `level_weight` the level's weight and `bary` the
// corner's barycentric one.
void addCorner(vec2 d, uvec3 products, float level_weight, float bary, uint level_seed, float texels_per_pixel,
               inout Sums s) {
  uint h = cornerHash(level_seed, products);
  // The nearest texel (the tile has several texels per pixel, and wraps by a mask): d is
  // within a few lattice spacings, so d × texels_per_pixel + 4096 is positive and its
  // truncation is the floor of d × texels_per_pixel, plus 4096.
  ivec2 texel = ivec2(d * texels_per_pixel + 4096.0) + ivec2(h & 0xFFFFu, h >> 16);
  texel &= u_tile_mask;
  s.grain += level_weight * bary * float(imageLoad(u_tile, (texel.y << u_tile_shift) | texel.x).r);
}

// The seed of lattice level `level`'s points in `space`. The corners' hashes mix it with a
// multiply: a sum is seed enough.
uint levelSeed(int space, int level) { return u_seed + uint(space) * 0x68E31DA4u + uint(level + 512) * 0x1B56C4E9u; }

// Adds the tile copies of lattice level `level` at P, with weight `weight` in all: `spacing`
// is the level's 2^level model units, and q is P / spacing. J is the projection's derivative
// at P (pixels per model unit), the same for every corner and both levels, in place of
// projecting each corner: it places a corner's projection off by about the perspective's
// change across the tetrahedron, at most ~3 % of the corner's distance on screen at a 45°
// field of view (the tetrahedron's size on screen is fixed), so a copy is read up to that
// much stretched, smoothly. Of the four corners the three of largest weight are read,
// chosen by selects (see the file's note).
void addLevel(vec3 q, float spacing, int level, float weight, int space, mat3x2 J, float texels_per_pixel, inout Sums s) {
  Tetrahedron t = kuhnScaled(q);
  uint level_seed = levelSeed(space, level);
  // pixel − a = J (P − corner) = J spacing (f − step): the lowest corner's, less each step.
  mat3x2 K = J * spacing;
  vec2 d0 = K * t.f;
  uvec3 p0 = cornerProducts(t.c);
  vec2 d1 = d0 - K * t.i1, d2 = d0 - K * t.i2, d3 = d0 - (K[0] + K[1] + K[2]);
  uvec3 p1 = stepProducts(p0, t.i1), p2 = stepProducts(p0, t.i2), p3 = p0 + kCornerMultipliers;
  vec4 w = t.w;
  float least = min(min(w.x, w.y), min(w.z, w.w));
  // k0 … k2: whether the corner dropped (the first of least weight) is 0, 1 or 2 (else 3);
  // the three kept, in order, with their weights less the least.
  bool k0 = w.x == least, k1 = !k0 && w.y == least, k2 = !k0 && !k1 && w.z == least;
  vec3 kept = vec3(k0 ? w.y : w.x, (k0 || k1) ? w.z : w.y, (k0 || k1 || k2) ? w.w : w.z) - least;
  addCorner(k0 ? d1 : d0, k0 ? p1 : p0, weight, kept.x, level_seed, texels_per_pixel, s);
  addCorner((k0 || k1) ? d2 : d1, (k0 || k1) ? p2 : p1, weight, kept.y, level_seed, texels_per_pixel, s);
  addCorner((k0 || k1 || k2) ? d3 : d2, (k0 || k1 || k2) ? p3 : p2, weight, kept.z, level_seed, texels_per_pixel, s);
  s.w2 += weight * weight * dot(kept, kept);
}

// cos(π/2 · t) for t in [0, 1]: sin(π/2 · (1 − t)) by its Taylor series to x⁷, within 2e-4
// (a software rasteriser's sin and cos reduce the range first, at several times the cost).
float quarterSine(float t) {
  float x = 1.5707963 * (1.0 - t), x2 = x * x;
  return x * (1.0 - x2 * (1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0))));
}

void shadePixel() {
  vec2 pixel = PIXEL_COORD;
  vec2 ndc = pixel * u_ndc_per_pixel - 1.0;
  // Without divisions where a product does: a software rasteriser pays for each.
  float w, per_w;  // clip w (the distance along the view axis), and 1 / w
#ifdef BACKGROUND
  const int space = 0;
  vec3 P = domePoint(ndc, w);
  per_w = 1.0 / w;
#else
  ivec2 p = ivec2(pixel);
  float depth = texelFetch(u_depth, p, 0).r;
#ifdef SINGLE_OBJECT
  const int space = 1;
#else
  int space = int(texelFetch(u_surface, p, 0).a * 255.0 + 0.5);
#endif
  vec4 m = u_spaces[space].to_model * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  w = 1.0 / m.w;  // m.w = 1 / w: to_model inverts the projection
  per_w = m.w;
  vec3 P = m.xyz * w;
#endif
  // d pixel / dP: the projection's derivative at P (its columns are the model axes').
  mat4 to_clip = u_spaces[space].to_clip;
  vec2 scale = 0.5 * u_viewport * per_w;
  mat3x2 J = mat3x2(scale * (vec2(to_clip[0][0], to_clip[0][1]) - ndc * to_clip[0][3]),
                    scale * (vec2(to_clip[1][0], to_clip[1][1]) - ndc * to_clip[1][3]),
                    scale * (vec2(to_clip[2][0], to_clip[2][1]) - ndc * to_clip[2][3]));
  // The lattice level, log2 of the patch in model units, split by its bits: the octave
  // `lower` is the exponent, and the place in it t = log2 m of the mantissa m = 2^t in
  // [1, 2), by a cubic exact at both ends (within 1.5e-4). The spacing 2^lower and its
  // inverse are made from bits too (the clamp keeps them normal floats for any scene): log2
  // and ldexp cost a software rasteriser a dozen instructions or more each (~0.8 ms of ~19
  // at 1024x768).
  int bits = floatBitsToInt(u_patch_pixels * modelPerPixel(space, w));
  int lower = clamp((bits >> 23) - 127, -120, 120);
  float mantissa = intBitsToFloat((bits & 0x7FFFFF) | 0x3F800000), u = mantissa - 1.0;
  float t = u + u * (1.0 - u) * (0.43807325 + u * (-0.23669342 + u * 0.08030730));
  float spacing = intBitsToFloat((127 + lower) << 23), per_spacing = intBitsToFloat((127 - lower) << 23);
  // The two lattices around P's level, weighted cos θ and sin θ with θ = π/2 (level − lower):
  // the mix turns at a constant rate while the camera moves in or out, over a whole octave
  // (a narrower band turns faster and costs more warping error in a dolly than it saves).
  // With GRAIN_ON_SURFACE the lower level's copies are read 2^t times finer, the upper's
  // half that: the grain grows and shrinks with the surface between octaves, as a texture
  // pinned to it would.
#ifdef GRAIN_ON_SURFACE
  float texels_per_pixel = u_texels_per_pixel * mantissa;
#else
  float texels_per_pixel = u_texels_per_pixel;
#endif
  Sums s;
  s.grain = 0.0;
  s.w2 = 0.0;
  float marks = 0.0;
  addLevel(P * per_spacing, spacing, lower, quarterSine(t), space, J, texels_per_pixel, s);
#ifdef GRAIN_ON_SURFACE
  texels_per_pixel *= 0.5;
#endif
  addLevel(P * (0.5 * per_spacing), 2.0 * spacing, lower + 1, quarterSine(1.0 - t), space, J, texels_per_pixel, s);
#ifdef PAPER_MARKS
  {
    // The marks' level, floor(level + 0.5) + 2, and the lattice point nearest P on it (see
    // the marks' note above).
    bool upper = t >= 0.5;
    float turn = upper ? t - 0.5 : t + 0.5, steps = upper ? 8.0 : 4.0;
    vec3 q = P * (per_spacing * (upper ? 0.125 : 0.25)), point = floor(q + 0.5);
    vec2 d = (J * (spacing * steps)) * (q - point);
    uint h = cornerHash(levelSeed(space, lower + (upper ? 3 : 2)), cornerProducts(ivec3(point)));
    // The lattice spacing on screen, in grain spacings: steps / mantissa.
    float fade = smoothstep(0.0, 1.0, 20.0 * turn) * smoothstep(0.0, 1.0, 20.0 - 20.0 * turn);
    marks += fade * pointMarks(d, h, steps * steps, mantissa * mantissa);
  }
#endif
  float grain = s.w2 > 0.0 ? s.grain * inversesqrt(s.w2) * u_tile_scale : 0.0;
#ifdef MOTTLE
  {
    // Bilinear between the four nearest cells' centres.
    vec2 x = pixel * u_mottle_texels - 0.5, f = fract(x);
    ivec2 c = ivec2(floor(x)), last = imageSize(u_mottle_image) - 1;
    ivec2 lo = clamp(c, ivec2(0), last), hi = clamp(c + 1, ivec2(0), last);
    float bottom = mix(imageLoad(u_mottle_image, lo).r, imageLoad(u_mottle_image, ivec2(hi.x, lo.y)).r, f.x);
    float top = mix(imageLoad(u_mottle_image, ivec2(lo.x, hi.y)).r, imageLoad(u_mottle_image, hi).r, f.x);
    marks += mix(bottom, top, f.y);
  }
#endif
  o_canvas = vec2(grain, marks);
}
#include "pixel_main.glsl"
