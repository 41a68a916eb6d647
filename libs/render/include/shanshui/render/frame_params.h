// The frame's uniform block in C++: the members come from shaders/common/frame_params.glsl,
// the one definition GLSL reads too.
#pragma once

#include <type_traits>

#include "shanshui/render/gpu_block.h"

namespace shanshui::render {

struct FrameInputs;

namespace gpu {

#include "common/frame_params.glsl"

#define SHANSHUI_GPU_STRUCT FrameParams
struct FrameParams {
  SHANSHUI_FRAME_PARAMS(SHANSHUI_GPU_DECLARE)
};
inline constexpr FieldOffset kFrameParamsFields[] = {SHANSHUI_FRAME_PARAMS(SHANSHUI_GPU_OFFSET)};
#undef SHANSHUI_GPU_STRUCT

static_assert(placedAsGlsl(kFrameParamsFields), "a FrameParams member is not where std140 puts it");
static_assert(sizeof(FrameParams) % 16 == 0, "FrameParams must fill whole 16-byte slots");
static_assert(std::is_trivially_copyable_v<FrameParams>);

}  // namespace gpu

//! The block's values for a frame (frame_params.glsl says what each member is).
gpu::FrameParams frameParams(const FrameInputs& in);

//! The uniform-block binding the frame's block is bound at (frame.glsl).
inline constexpr unsigned kFrameBlockBinding = 1;

}  // namespace shanshui::render
