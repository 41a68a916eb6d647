// Fuzz target for image headers and bodies through OpenImageIO, with the extension given by
// SHANSHUI_FUZZ_FORMAT (.png, .jpg, .tif, .pgm): a loaded image is finite and in budget.
#include <cmath>

#include "fuzz_input.h"
#include "shanshui/image/image_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shanshui;
  const fuzz::ScratchFile file(data, size, SHANSHUI_FUZZ_FORMAT);
  fuzz::expectParsedOrRefused([&] {
    const image::Image img = image::loadImage(file.path());
    SHANSHUI_CHECK(static_cast<long long>(img.width) * img.height <= image::kMaxImagePixels);
    for (float v : img.pixels) SHANSHUI_CHECK(std::isfinite(v));
  });
  return 0;
}
