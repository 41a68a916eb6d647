// Per-object parameters of the ink pass, indexed by the G-buffer's object id − 1.
// Layout matches ObjectParamsGpu in libs/render/src/ink_renderer.cpp (std430).
struct ObjectParams {
  vec4 line_color;   // rgb, curve_factor
  vec4 bg_color;     // rgb, Curv0 threshold
  vec4 line_misc;    // soft width, silhouette N·V, depth-edge jump, flags
  vec4 tones;        // C1..C4
  vec4 thresholds;   // t1..t4
  vec4 shade_misc;   // C5, sigma, beta, erosion
  vec4 shade_misc2;  // noise amplitude, 1 / R_InnerTexFactor, flags, unused
};

layout(std430, binding = 0) readonly buffer Objects { ObjectParams objects[]; };

const int kLinesOn = 1;       // line_misc.w bits
const int kNormalOnly = 2;    // small object: N·V lines only
const int kShadingOn = 1;     // shade_misc2.z bits
const int kHalfLambert = 2;
const int kLineValue = 4;
const int kWrinkled = 8;
