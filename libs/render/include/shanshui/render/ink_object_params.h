// The ink pass's per-object parameter block in C++: the members and flag bits come from
// shaders/ink/ink_object_params.glsl, the one definition GLSL reads too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <glm/glm.hpp>

namespace shanshui::render::gpu {

using vec3 = glm::vec3;
using vec4 = glm::vec4;
using uint = std::uint32_t;

#include "ink/ink_object_params.glsl"

#define SHANSHUI_DECLARE_FIELD(type, name) type name;
struct ObjectParams {
  SHANSHUI_OBJECT_PARAMS(SHANSHUI_DECLARE_FIELD)
};
#undef SHANSHUI_DECLARE_FIELD

//! Each member's name and C++ offset, for the test that compares them with the driver's.
struct FieldOffset {
  const char* name;
  std::size_t offset;
};
#define SHANSHUI_FIELD_OFFSET(type, name) FieldOffset{#name, offsetof(ObjectParams, name)},
inline constexpr FieldOffset kObjectParamsFields[] = {SHANSHUI_OBJECT_PARAMS(SHANSHUI_FIELD_OFFSET)};
#undef SHANSHUI_FIELD_OFFSET

// std140 / std430 rules for these member types: vec3 and vec4 start at a multiple of 16,
// scalars at a multiple of 4, and the block is a whole number of 16-byte slots (std140's
// array stride), so C++ and GLSL agree on every offset.
template <typename T>
constexpr bool placedAsGlsl(std::size_t offset) {
  return (std::is_same_v<T, vec3> || std::is_same_v<T, vec4>) ? offset % 16 == 0 : offset % 4 == 0;
}
#define SHANSHUI_CHECK_PLACEMENT(type, name)                      \
  static_assert(placedAsGlsl<type>(offsetof(ObjectParams, name)), \
                "ObjectParams::" #name " is not where std140/std430 puts it");
SHANSHUI_OBJECT_PARAMS(SHANSHUI_CHECK_PLACEMENT)
#undef SHANSHUI_CHECK_PLACEMENT
static_assert(sizeof(ObjectParams) % 16 == 0, "ObjectParams must fill whole 16-byte slots");
static_assert(std::is_trivially_copyable_v<ObjectParams>);

}  // namespace shanshui::render::gpu
