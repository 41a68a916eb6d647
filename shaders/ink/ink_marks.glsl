// Texture strokes (cun) as discrete brush marks (issue 45), beside seed 001's wrinkle
// texture: hemp-fibre marks (long, thin, bowed, tapering at both ends) or axe-cut marks
// (short wedges, broad at the downhill end, turned a little off the fall line), laid down
// the fall line on a jittered lattice over the object's horizontal plane. A lattice cell
// holds at most one mark; whether it does is a random threshold against the density there,
// which grows on the shadowed side and near ridges, so lit slopes keep few marks and no
// regular dash pattern forms. Two power-of-two octaves around the marks' size on screen
// are blended, as the slope wrinkles do, so marks stay on the land and keep their size.

#include "ink_hash.glsl"

const uint kMarksHemp = 1u, kMarksAxe = 2u;

// Four random numbers in [0, 1) from one hash.
vec4 unpack4(uint h) {
  return vec4(h & 0xffu, (h >> 8) & 0xffu, (h >> 16) & 0xffu, h >> 24) / 256.0;
}

// The darkest mark over lattice point q (cells), marks running along dir (unit, in the
// lattice's plane), each kept where `density` beats its cell's threshold (a soft step, so
// a mark fades instead of being cut where the density changes under it). A mark reaches at
// most half a cell from its centre, which lies in its cell, so the 2 × 2 cells nearest q
// hold every mark that can cover it.
float marksOctave(vec2 q, vec2 dir, float density, uint style, uint seed) {
  vec2 perp = vec2(-dir.y, dir.x);
  ivec2 base = ivec2(floor(q - 0.5));
  uvec2 salt = uvec2(seed, seed * 0x9e3779b9u);
  // First which of the four cells hold a mark that is kept and within reach of q (one hash
  // each: a centre lies within half a cell of q for ~0.8 of them), then the shapes of those
  // alone, in a loop as long as the most any pixel needs. A software rasteriser runs both
  // sides of a branch for a whole group of pixels, but leaves a loop once all are done: the
  // shapes cost one or two turns instead of four.
  uint todo = 0u;
  for (int k = 0; k < 4; ++k) {
    ivec2 c = base + ivec2(k & 1, k >> 1);
    vec4 a = unpack4(cellHash(uvec2(c + 32768) ^ salt));
    vec2 d = q - (vec2(c) + a.xy);
    if (dot(d, d) < 0.25 && density > a.z - 0.06) todo |= 1u << k;
  }
  float ink = 0.0;
  while (todo != 0u) {
    int k = findLSB(todo);
    todo &= todo - 1u;
    ivec2 c = base + ivec2(k & 1, k >> 1);
    uint h = cellHash(uvec2(c + 32768) ^ salt);
    vec4 a = unpack4(h);
    vec2 d = q - (vec2(c) + a.xy);
    float keep = smoothstep(a.z - 0.06, a.z + 0.06, density);
    vec4 b = unpack4(cellHash(uvec2(h, seed + 7u)));
    float cover;
    if (style == kMarksAxe) {
      // A wedge turned up to ±25 degrees: its point uphill, its broad end downhill.
      // cos and sin to the cubic and quadratic terms: within 0.3 % at 25 degrees.
      float turn = (b.x - 0.5) * 0.87, turn2 = turn * turn;
      float cs = 1.0 - 0.5 * turn2, sn = turn * (1.0 - turn2 / 6.0);
      vec2 along_dir = cs * dir + sn * perp;
      float along = dot(d, along_dir), across = dot(d, vec2(-along_dir.y, along_dir.x));
      float half_length = 0.3 + 0.12 * b.y;  // with the ±25° turn, at most half a cell along x or y
      float t = along / half_length;        // -1 uphill point .. 1 broad end
      float width = (0.04 + 0.1 * b.z) * clamp(0.5 + 0.5 * t, 0.0, 1.0);
      cover = (1.0 - smoothstep(0.85, 1.0, abs(t))) * (1.0 - smoothstep(0.7 * width, width, abs(across)));
    } else {
      // A long hemp fibre down the slope, bowed once to one side as a brush drawn down a
      // slope bows, with a slight S over it, tapering to both ends. (A fibre that waved
      // across itself twice read as a stray hair; bundles of three as tally marks.)
      float along = dot(d, dir), across = dot(d, perp);
      float half_length = 0.36 + 0.1 * b.y;
      float t = along / half_length;
      across -= (b.x - 0.5) * 0.1 * (1.0 - t * t) + 0.01 * sin(6.2832 * (t + b.x));
      float width = (0.022 + 0.018 * b.z) * sqrt(max(1.0 - t * t, 0.0));
      cover = abs(t) < 1.0 ? 1.0 - smoothstep(0.5 * width, width + 1e-4, abs(across)) : 0.0;
    }
    ink = max(ink, keep * cover * (0.55 + 0.45 * b.w));
  }
  return ink;
}

// The log2 of a lattice cell's size in the units of uv, for cells spacing_px pixels across
// on screen where uv moves by duv_dx, duv_dy per pixel (their geometric mean); NaN-free,
// -inf-free: a degenerate footprint gives a vanishing cell, which draws nothing.
float marksScale(vec2 duv_dx, vec2 duv_dy, float spacing_px) {
  float det = abs(duv_dx.x * duv_dy.y - duv_dy.x * duv_dx.y);
  return det > 1e-30 ? log2(max(spacing_px * sqrt(det), 1e-30)) : -100.0;
}

// The marks' ink at the point uv of a plane (cells of 2^scale of its units); down: the fall
// line there in the same plane (zero on flat ground); density in [0, 1].
float textureMarks(vec2 uv, float scale, vec2 down, float density, uint style, uint seed) {
  if (density <= 0.0 || scale <= -99.0) return 0.0;
  vec2 dir = length(down) > 1e-6 ? normalize(down) : vec2(0.0, 1.0);
  float level = floor(scale);
  float size0 = exp2(level);
  // One octave holds the marks over most of a zoom step (cells 0.7-1.4 times the size asked
  // for), the two cross-fading only over the middle fifth of it: a pixel computes one
  // lattice most of the time, and a mark is drawn at full strength instead of as the
  // half-faded sum of two.
  float blend = smoothstep(0.4, 0.6, scale - level);
  // Each octave its own lattice (a different seed), so the coarser one's marks are not
  // the finer one's doubled. A loop over the octaves needed, not two calls: it ends after
  // one turn where every pixel of a group needs only one.
  int octave = int(level);
  float a = 0.0, b = 0.0;
  for (int k = blend < 1.0 ? 0 : 1, last = blend > 0.0 ? 1 : 0; k <= last; ++k) {
    float ink = marksOctave(uv / (k == 0 ? size0 : 2.0 * size0), dir, density, style,
                            seed + uint((octave + k) & 1023) * 131u);
    if (k == 0) a = ink; else b = ink;
  }
  return mix(a, b, blend);
}

// Broad wet strokes (objects.N.marks.wash): groups of up to three strokes side by side (up to
// seven, closer together, as wash_width broadens them into a brush laid on its side), as a
// painter lays a wet cun, each with a dark round head uphill and a body that pales and parts
// into dry-brush streaks towards its tail, the group turned a little and gently bent. Two
// lattices, the second offset by half a cell along both axes, so groups stand in staggered
// rows as strokes laid overlapping down a slope; where they overlap the ink is layered
// (1 - (1 - a)(1 - b)), as one wet stroke laid over another darkens it. A group's centre
// stays within 0.08 of its cell's middle and the group within 0.42 of its centre, so of
// each lattice only q's own cell can cover q: two cells a pixel, not four.
//
// As textureMarks, the work a pixel may skip sits in loops, not branches: a software
// rasteriser runs both sides of a branch for a whole group of pixels, but leaves a loop once
// none of them has a turn left.

// A group at d from its centre (its cell's hash h): its second hash's numbers b, the
// point along and across it (turned together up to ±15 degrees, cos and sin to the cubic
// and quadratic terms, and bent to one side, heads uphill), the brush's hairs there, its
// strokes' spacing: 2m + 1 of them, gap apart, for strokes `breadth` times their thin
// width, and how far their heads slant across the group.
void washFrame(vec2 d, vec2 dir, uint h, float breadth, uint seed, out vec4 b, out float along, out float across,
               out float hair, out int m, out float gap, out float slant) {
  b = unpack4(cellHash(uvec2(h, seed + 7u)));
  // Each group its own size, from 0.55 of the cell's to all of it (more of them large), and
  // its heads on a slant of up to ±0.45 along per unit across, as a brush laid on its side
  // lands heel first: strokes of one size with their heads in a row read as a comb.
  vec4 e = unpack4(cellHash(uvec2(h, seed + 11u)));
  d /= 0.55 + 0.45 * sqrt(e.x);
  slant = (e.y - 0.5) * 0.9;
  float turn = (b.x - 0.5) * 0.52, turn2 = turn * turn;
  float cs = 1.0 - 0.5 * turn2, sn = turn * (1.0 - turn2 / 6.0);
  vec2 along_dir = cs * dir + sn * vec2(-dir.y, dir.x);
  along = dot(d, along_dir);
  across = dot(d, vec2(-along_dir.y, along_dir.x));
  across -= (b.x < 0.5 ? 0.025 : -0.025) * (1.0 - 5.0 * along * along);
  // The brush's hairs: value noise across the group, running its length, the gaps between
  // them widening towards the tail, where the brush runs dry.
  float u = 36.0 * across + 17.0 * b.w, f = fract(u);
  uint hu = uint(int(floor(u)) + 64) ^ h;
  hair = mix(float(cellHash(uvec2(hu, 3u)) >> 8) / 16777216.0, float(cellHash(uvec2(hu + 1u, 3u)) >> 8) / 16777216.0,
             f * f * (3.0 - 2.0 * f));
  // Strokes side by side, each its own length (half: 0.24-0.34, less towards a broad group's
  // edges), start, width (half: 0.04-0.065) and ink, and any but the middle one missing from
  // a third of the groups. Thin (breadth 1): three 0.13 apart, so groups of one to three.
  // Broader: up to seven, closer than their width, as the hairs of a brush laid on its
  // side, their heads staggered. Narrower than 1: thinner strokes closer together. In every
  // case a stroke's half-width is under its gap, so of the strokes only the two nearest a
  // point can cover it.
  float half_extent = 0.13 * min(breadth, 2.15);
  m = max(1, int(half_extent / 0.1 + 0.5));
  gap = half_extent / float(m);
}

// Stroke j (0 .. 2m) of a group framed by washFrame: its ink at (along, across).
float washStroke(int j, float along, float across, float hair, int m, float gap, float breadth, float slant, vec4 a,
                 vec4 b) {
  float r1 = fract(b.y + 0.618 * float(j)), r2 = fract(b.z + 0.382 * float(j)), r3 = fract(a.w + 0.618 * float(j));
  float offset = gap * float(j - m);
  // The slant moves the stroke along by `shift` and takes as much off its length, so it
  // ends no farther from the centre than a stroke without one (at least 0.05 is left).
  float shift = slant * offset;
  float len = max((0.24 + 0.1 * r1) * (1.0 - 2.5 * max(abs(offset) - 0.13, 0.0)) - abs(shift), 0.05);
  float t = (along - 0.08 * min(breadth, 1.5) * (r2 - 0.5) - shift) / len;  // -1 the head .. 1 the tail
  // Round at the head, full through the body, narrowing to the tail.
  float width =
      min(breadth, 1.0) * (0.04 + 0.025 * r1) * sqrt(clamp((1.0 + t) * 3.0, 0.0, 1.0)) * (1.0 - 0.5 * max(t, 0.0));
  float s = (across - offset) / max(width, 1e-4);
  float cover = (1.0 - smoothstep(0.85, 1.0, abs(t))) * (1.0 - smoothstep(0.6, 1.0, abs(s))) *
                (j != m && r3 < 0.33 ? 0.0 : 0.8 + 0.2 * r3);
  // Drier and paler towards the tail.
  float dry = 0.05 + 0.6 * smoothstep(-0.3, 1.0, t);
  return cover * smoothstep(dry - 0.12, dry + 0.12, hair) * mix(1.0, 0.45, smoothstep(-1.0, 1.0, t));
}

// The ink of one group (its cell's hash h, the hash's first numbers a) at d from its centre:
// the two strokes nearest d across the group, the second laid over the first, darker where
// both lie (wash_probe.comp holds this to all 2m + 1 strokes layered).
float washGroup(vec2 d, vec2 dir, uint h, vec4 a, float density, float breadth, uint seed) {
  float keep = smoothstep(a.z - 0.06, a.z + 0.06, density);
  vec4 b;
  float along, across, hair, gap, slant;
  int m;
  washFrame(d, dir, h, breadth, seed, b, along, across, hair, m, gap, slant);
  float pos = across / gap + float(m);
  int j0 = clamp(int(floor(pos + 0.5)), 0, 2 * m);
  int j1 = clamp(pos > float(j0) ? j0 + 1 : j0 - 1, 0, 2 * m);
  float ink = 0.0;
  for (int n = 0, strokes = breadth > 1.0 && j1 != j0 ? 2 : 1; n < strokes; ++n)
    ink += (1.0 - ink) * washStroke(n == 0 ? j0 : j1, along, across, hair, m, gap, breadth, slant, a, b);
  return keep * ink;
}

// Lattice k's cell over lattice point q (the second lattice offset by half a cell, with a
// seed of its own, s): its hash, and q's offset d from the cell's group centre.
uint washCell(vec2 q, int k, uint seed, out uint s, out vec2 d) {
  vec2 p = q + 0.5 * float(k);
  s = k == 0 ? seed : seed ^ 0x68e31da4u;
  ivec2 c = ivec2(floor(p));
  uint h = cellHash(uvec2(c + 32768) ^ uvec2(s, s * 0x9e3779b9u));
  d = p - (vec2(c) + 0.5 + 0.16 * (unpack4(h).xy - 0.5));
  return h;
}

// The wet strokes of both lattices over lattice point q (cells): first which of the two
// cells hold a group that is kept and within reach of q (one hash each), then those alone.
float washOctave(vec2 q, vec2 dir, float density, float breadth, uint seed) {
  uint todo = 0u, s;
  vec2 d;
  for (int k = 0; k < 2; ++k) {
    uint h = washCell(q, k, seed, s, d);
    if (dot(d, d) < 0.1764 && density > unpack4(h).z - 0.06) todo |= 1u << k;
  }
  float ink = 0.0;
  while (todo != 0u) {
    int k = findLSB(todo);
    todo &= todo - 1u;
    uint h = washCell(q, k, seed, s, d);
    ink += (1.0 - ink) * washGroup(d, dir, h, unpack4(h), density, breadth, s);
  }
  return ink;
}

// The wet strokes' ink at uv of a plane (cells of 2^scale of its units), down the direction
// `down` there (unit or zero: then straight down the plane's v). Across the two octaves
// around the scale the groups are shared out, not faded: each lattice keeps its share of
// them at full strength.
float washMarks(vec2 uv, float scale, vec2 down, float density, float breadth, uint seed) {
  vec2 dir = length(down) > 1e-6 ? normalize(down) : vec2(0.0, -1.0);
  float level = floor(scale);
  float size0 = exp2(level);
  float blend = smoothstep(0.4, 0.6, scale - level);
  int octave = int(level);
  float ink = 0.0;
  for (int k = blend < 1.0 ? 0 : 1, last = blend > 0.0 ? 1 : 0; k <= last; ++k)
    ink += (1.0 - ink) * washOctave(uv / (k == 0 ? size0 : 2.0 * size0), dir, density * (k == 0 ? 1.0 - blend : blend),
                                    breadth, seed + uint((octave + k) & 1023) * 131u);
  return ink;
}
