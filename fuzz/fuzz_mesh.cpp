// Fuzz target for the mesh readers: OBJ, PLY, OFF, or glTF (.gltf, .glb; through Assimp),
// chosen by SHANSHUI_FUZZ_FORMAT at compile time (one binary per format). Every face of a
// mesh read has three corners or more, each an index of one of its vertices.
#include "fuzz_input.h"
#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shanshui;
  const fuzz::ScratchFile file(data, size, SHANSHUI_FUZZ_FORMAT);
  fuzz::expectParsedOrRefused([&] {
    const mesh::PolygonSoup soup = mesh::readPolygonSoup(file.path());
    for (const auto& face : soup.faces) {
      SHANSHUI_CHECK(face.size() >= 3);
      for (std::uint32_t i : face) SHANSHUI_CHECK_LT(i, soup.positions.size());
    }
  });
  return 0;
}
