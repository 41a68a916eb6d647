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
#elif defined(OBJECTS)
// OBJECTS objects: a uniform block too, indexed per pixel. On llvmpipe a storage buffer
// indexed per pixel made the painting sample's ink and lines passes 3 and 2.6 times as
// slow (84 and 98 ms against 28 and 38 at 1024², three terrains).
layout(std140, binding = 0) uniform Objects { ObjectParams objects[OBJECTS]; };
#else
// More objects than a uniform block holds on this driver (GL guarantees 16 KiB: 93 objects).
layout(std430, binding = 0) readonly buffer Objects { ObjectParams objects[]; };
#endif
