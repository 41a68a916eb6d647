// GLSL files from shaders/, embedded into the binary at build time.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace shanshui::render {

namespace detail {
struct EmbeddedShader {
  const char* name;
  const char* source;
};
extern const EmbeddedShader kEmbeddedShaders[];
}  // namespace detail

//! The text of shaders/<name>. Throws Error for an unknown name.
std::string_view shaderSource(std::string_view name);

//! Every embedded shader file name.
std::vector<std::string> shaderNames();

}  // namespace shanshui::render
