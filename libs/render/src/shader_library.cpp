#include "shanshui/render/shader_library.h"

#include <map>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"

namespace shanshui::render {

namespace {
std::filesystem::path& shaderDirectory() {
  static std::filesystem::path dir;
  return dir;
}
}  // namespace

void setShaderDirectory(const std::filesystem::path& dir) {
  shaderDirectory() = dir;
}

std::string_view shaderSource(std::string_view name) {
  if (!shaderDirectory().empty()) {
    const std::filesystem::path file = shaderDirectory() / std::string(name);
    std::error_code ec;
    if (std::filesystem::exists(file, ec)) {  // through the input gate; absent: the embedded copy
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
