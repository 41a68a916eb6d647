#include "shanshui/render/shader_library.h"

#include <filesystem>
#include <map>
#include <string>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"

namespace shanshui::render {

namespace {
std::filesystem::path& shaderDirectory() {
  static std::filesystem::path dir;
  return dir;
}

// The file of shader `name` under `dir`: dir/name (a flat copy), else the file of that name
// in a folder below dir (the repository's shaders/ has a folder per pass); empty if none.
std::filesystem::path findShaderFile(const std::filesystem::path& dir, std::string_view name) {
  std::error_code ec;
  const std::filesystem::path flat = dir / std::string(name);
  if (std::filesystem::is_regular_file(flat, ec)) return flat;
  for (std::filesystem::recursive_directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->path().filename() == name && it->is_regular_file(ec)) return it->path();
  }
  return {};
}
}  // namespace

void setShaderDirectory(const std::filesystem::path& dir) {
  shaderDirectory() = dir;
}

std::string_view shaderSource(std::string_view name) {
  if (!shaderDirectory().empty()) {
    const std::filesystem::path file = findShaderFile(shaderDirectory(), name);
    if (!file.empty()) {  // through the input gate; absent: the embedded copy
      static std::map<std::string, std::string, std::less<>> loaded;  // keeps the views valid
      std::string& slot = loaded[std::string(name)];
      slot = readInputFile(file, "a GLSL shader", kMaxTextInputBytes);
      return slot;
    }
  }
  for (const auto* s = detail::kEmbeddedShaders; s->name; ++s) {
    if (name == s->name) return s->source;
  }
  throw makeError("shader '", name, "' is not embedded (is it under shaders/?)");
}

std::vector<std::string> shaderNames() {
  std::vector<std::string> names;
  for (const auto* s = detail::kEmbeddedShaders; s->name; ++s) names.emplace_back(s->name);
  return names;
}

}  // namespace shanshui::render
