// The ink pass's per-object parameter block in C++: the members and flag bits come from
// shaders/ink/ink_object_params.glsl, the one definition GLSL reads too.
#pragma once

#include <type_traits>

#include "shanshui/render/gpu_block.h"

namespace shanshui::render::gpu {

#include "ink/ink_object_params.glsl"

#define SHANSHUI_GPU_STRUCT ObjectParams
struct ObjectParams {
  SHANSHUI_OBJECT_PARAMS(SHANSHUI_GPU_DECLARE)
};
inline constexpr FieldOffset kObjectParamsFields[] = {SHANSHUI_OBJECT_PARAMS(SHANSHUI_GPU_OFFSET)};
#undef SHANSHUI_GPU_STRUCT

// std140 / std430 place each member where C++ does (a GL test compares every offset with the
// driver's), and the block is a whole number of 16-byte slots (std140's array stride).
static_assert(placedAsGlsl(kObjectParamsFields), "an ObjectParams member is not where std140/std430 puts it");
static_assert(sizeof(ObjectParams) % 16 == 0, "ObjectParams must fill whole 16-byte slots");
static_assert(std::is_trivially_copyable_v<ObjectParams>);

}  // namespace shanshui::render::gpu
