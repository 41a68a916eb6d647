#include "shanshui/render/shader_library.h"

#include "shanshui/core/error.h"

namespace shanshui::render {

std::string_view shaderSource(std::string_view name) {
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
