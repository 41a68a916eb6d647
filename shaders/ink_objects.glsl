// Per-object parameters of the ink pass, indexed by the G-buffer's object id − 1.
// Layout matches ObjectParamsGpu in libs/render/src/ink_renderer.cpp (std430, and std140
// too: the struct is vec4s only).
struct ObjectParams {
  vec4 line_color;   // rgb, curve_factor
  vec4 bg_color;     // rgb, Curv0 threshold
  vec4 line_misc;    // soft width, silhouette N·V, depth-edge jump, flags
  vec4 tones;        // C1..C4
  vec4 thresholds;   // t1..t4
  vec4 shade_misc;   // C5, sigma, beta, erosion
  vec4 shade_misc2;  // noise amplitude, 1 / R_InnerTexFactor, flags, unused
};

#ifdef SINGLE_OBJECT
// One object: a uniform block, loaded once for all pixels. A storage buffer is read per
// pixel on a software rasteriser even at a constant index (the pass costs ~10 % more).
layout(std140, binding = 0) uniform Objects { ObjectParams objects[1]; };
#else
layout(std430, binding = 0) readonly buffer Objects { ObjectParams objects[]; };
#endif

const int kLinesOn = 1;       // line_misc.w bits
const int kNormalOnly = 2;    // small object: N·V lines only
const int kShadingOn = 1;     // shade_misc2.z bits
const int kHalfLambert = 2;
const int kLineValue = 4;
const int kWrinkled = 8;
