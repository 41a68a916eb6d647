// The frame's block (frame_params.glsl): bound at uniform-block binding 1 for every pass.
#ifndef FRAME_GLSL
#define FRAME_GLSL
#include "frame_params.glsl"
#define SHANSHUI_DECLARE_FRAME_FIELD(type, name) type name;
layout(std140, binding = 1) uniform FrameUniforms {
  SHANSHUI_FRAME_PARAMS(SHANSHUI_DECLARE_FRAME_FIELD)
};
#endif
