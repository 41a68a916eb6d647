// Per-object parameters of the ink pass, indexed by the G-buffer's object id − 1. The
// members and flag bits are defined in ink_object_params.glsl, shared with C++.
#include "ink_object_params.glsl"

#define SHANSHUI_DECLARE_FIELD(type, name) type name;
struct ObjectParams {
  SHANSHUI_OBJECT_PARAMS(SHANSHUI_DECLARE_FIELD)
};

#ifdef SINGLE_OBJECT
// One object: a uniform block, loaded once for all pixels. A storage buffer is read per
// pixel on a software rasteriser even at a constant index (the pass costs ~10 % more).
layout(std140, binding = 0) uniform Objects { ObjectParams objects[1]; };
#else
layout(std430, binding = 0) readonly buffer Objects { ObjectParams objects[]; };
#endif
