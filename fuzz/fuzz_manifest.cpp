// Fuzz target for batch manifests: splitting lines into words and reading a whole manifest.
#include <string>

#include "batch.h"
#include "fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shanshui;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string error;
  const auto words = tools::splitManifestLine(text.substr(0, text.find('\n')), &error);
  SHANSHUI_CHECK(words.empty() || error.empty());
  const fuzz::ScratchFile file(data, size, ".txt");
  fuzz::expectParsedOrRefused([&] {
    for (const tools::ManifestItem& item : tools::readManifest(file.path().string())) {
      SHANSHUI_CHECK(item.line >= 1);
      SHANSHUI_CHECK(item.args.empty() || item.error.empty());
    }
  });
  return 0;
}
