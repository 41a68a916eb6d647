// Fuzz target for scene files and --set: the input is a scene's JSON text; its first line,
// when it looks like KEY=VALUE, is also applied as a --set override.
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "shanshui/scene/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shanshui;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> sets;
  const std::string first = text.substr(0, text.find('\n'));
  if (first.find('=') != std::string::npos && first.size() < 4096) sets.push_back(first);
  const fuzz::ScratchFile file(data, size, ".json");
  fuzz::expectParsedOrRefused([&] { (void)scene::loadScene(file.path(), sets); });
  return 0;
}
