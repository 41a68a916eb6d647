// Fuzz target for the DEM readers: USGS ASCII DEM (.dem) or ESRI ASCII grid (.asc), chosen
// by SHANSHUI_FUZZ_FORMAT; a grid that loads must be consistent and meshable or refused.
#include "fuzz_input.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shanshui;
  const fuzz::ScratchFile file(data, size, SHANSHUI_FUZZ_FORMAT);
  fuzz::expectParsedOrRefused([&] {
    const terrain::Heightfield h = terrain::loadHeightfield(file.path(), {});
    SHANSHUI_CHECK_EQ(h.elevation.size(), static_cast<std::size_t>(h.columns) * h.rows);
    terrain::TerrainMeshOptions options;
    options.max_vertices = 4096;
    (void)terrain::heightfieldToMesh(h, options, nullptr, file.path().string());
  });
  return 0;
}
