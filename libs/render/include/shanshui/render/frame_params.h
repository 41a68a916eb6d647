// The frame's uniform block in C++: the members come from shaders/common/frame_params.glsl,
// the one definition GLSL reads too.
#pragma once

#include <cstddef>
#include <type_traits>

#include <glm/glm.hpp>

#include "shanshui/render/ink_object_params.h"  // the GLSL type names, FieldOffset

namespace shanshui::render {

struct FrameInputs;

namespace gpu {

using vec2 = glm::vec2;
using mat4 = glm::mat4;

#include "common/frame_params.glsl"

#define SHANSHUI_DECLARE_FIELD(type, name) type name;
struct FrameParams {
  SHANSHUI_FRAME_PARAMS(SHANSHUI_DECLARE_FIELD)
};
#undef SHANSHUI_DECLARE_FIELD

#define SHANSHUI_FIELD_OFFSET(type, name) FieldOffset{#name, offsetof(FrameParams, name)},
inline constexpr FieldOffset kFrameParamsFields[] = {SHANSHUI_FRAME_PARAMS(SHANSHUI_FIELD_OFFSET)};
#undef SHANSHUI_FIELD_OFFSET

// std140 for these member types: mat4, vec4 and vec3 start at a multiple of 16, vec2 at a
// multiple of 8, scalars at a multiple of 4.
template <typename T>
constexpr bool placedAsStd140(std::size_t offset) {
  if constexpr (std::is_same_v<T, mat4> || std::is_same_v<T, vec4> || std::is_same_v<T, vec3>)
    return offset % 16 == 0;
  else if constexpr (std::is_same_v<T, vec2>)
    return offset % 8 == 0;
  else
    return offset % 4 == 0;
}
#define SHANSHUI_CHECK_PLACEMENT(type, name)                       \
  static_assert(placedAsStd140<type>(offsetof(FrameParams, name)), \
                "FrameParams::" #name " is not where std140 puts it");
SHANSHUI_FRAME_PARAMS(SHANSHUI_CHECK_PLACEMENT)
#undef SHANSHUI_CHECK_PLACEMENT
static_assert(sizeof(FrameParams) % 16 == 0, "FrameParams must fill whole 16-byte slots");
static_assert(std::is_trivially_copyable_v<FrameParams>);

}  // namespace gpu

//! The block's values for a frame (frame_params.glsl says what each member is).
gpu::FrameParams frameParams(const FrameInputs& in);

//! The uniform-block binding the frame's block is bound at (frame.glsl).
inline constexpr unsigned kFrameBlockBinding = 1;

}  // namespace shanshui::render
