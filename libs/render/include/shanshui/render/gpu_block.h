// What the GPU blocks defined once for GLSL and C++ (an X-macro list of `F(type, name)` in a
// shaders/*_params.glsl) need on the C++ side: the GLSL type names, and the declaration of a
// block's struct and of its members' names and offsets, with a static check that each member
// lies where GLSL puts it. A header that includes a list defines SHANSHUI_GPU_STRUCT as the
// struct's name, declares with SHANSHUI_GPU_DECLARE and SHANSHUI_GPU_OFFSET, and undefines it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <glm/glm.hpp>

namespace shanshui::render::gpu {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using uint = std::uint32_t;

//! The alignment std140 and std430 give a member of these types: mat4, vec4 and vec3 start at
//! a multiple of 16, vec2 at a multiple of 8, scalars at a multiple of 4 (a vec3 followed by
//! a scalar fills one 16-byte slot, as in C++).
template <typename T>
constexpr std::size_t glslAlignment() {
  if constexpr (std::is_same_v<T, mat4> || std::is_same_v<T, vec4> || std::is_same_v<T, vec3>)
    return 16;
  else if constexpr (std::is_same_v<T, vec2>)
    return 8;
  else
    return 4;
}

//! A member's name and C++ offset (for the tests that compare them with the driver's), and
//! the alignment GLSL gives it.
struct FieldOffset {
  const char* name;
  std::size_t offset;
  std::size_t alignment;
};

//! Whether every member starts where GLSL puts it.
template <std::size_t N>
constexpr bool placedAsGlsl(const FieldOffset (&fields)[N]) {
  for (const FieldOffset& f : fields)
    if (f.offset % f.alignment != 0) return false;
  return true;
}

}  // namespace shanshui::render::gpu

#define SHANSHUI_GPU_DECLARE(type, name) type name;
#define SHANSHUI_GPU_OFFSET(type, name) \
  ::shanshui::render::gpu::FieldOffset{#name, offsetof(SHANSHUI_GPU_STRUCT, name), glslAlignment<type>()},
