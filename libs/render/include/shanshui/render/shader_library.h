// GLSL files from shaders/, embedded into the binary at build time.
#pragma once

#include <filesystem>
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

//! The text of shaders/<name>: from the directory set by setShaderDirectory() when the file
//! is there (read anew on every call, for hot reload), else the embedded copy. Throws Error
//! for an unknown name.
std::string_view shaderSource(std::string_view name);

//! Reads shaders from `dir` instead of the embedded copies (empty: embedded only).
void setShaderDirectory(const std::filesystem::path& dir);

//! Every embedded shader file name.
std::vector<std::string> shaderNames();

}  // namespace shanshui::render
