// Fuzz target for the DEM readers: USGS ASCII DEM (.dem) or ESRI ASCII grid (.asc), chosen
// by SHANSHUI_FUZZ_FORMAT; a grid that loads must be consistent and meshable or refused, and
// smoothing its storage steps (what the renderer does on load) keeps every sample within
// half a step of its stored height, no-data as no-data, and finite heights finite; made
// finer (upsample), it keeps its samples and its holes and stays finite.
#include <algorithm>
#include <cmath>

#include "fuzz_input.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"

namespace {

// Smoothing its storage steps keeps every sample within half a step, no-data as no-data and
// finite heights finite; made finer, the grid keeps its samples and holes and stays finite.
void checkSmoothed(shanshui::terrain::Heightfield& h) {
  using namespace shanshui;
  const std::vector<double> stored = h.elevation;
  const terrain::Dequantized d = terrain::dequantize(h);
  SHANSHUI_CHECK(std::isfinite(d.step) && d.step >= 0.0);
  for (std::size_t i = 0; i < stored.size(); ++i) {
    SHANSHUI_CHECK_EQ(std::isnan(h.elevation[i]), std::isnan(stored[i]));
    if (std::isnan(stored[i])) continue;
    SHANSHUI_CHECK(std::isfinite(h.elevation[i]) == std::isfinite(stored[i]));
    if (std::isfinite(stored[i]))
      SHANSHUI_CHECK_LE(std::abs(h.elevation[i] - stored[i]), 0.5 * d.step * (1.0 + 1e-5) + 1e-6 * std::abs(stored[i]));
  }
  // Made finer (what a lone coarse DEM gets): the smoothed samples kept exactly, a new
  // sample no data only beside no data, and finite everywhere else, however large the
  // heights.
  if (h.elevation.size() <= 65536) {
    terrain::Heightfield fine = h;
    terrain::upsample(fine, 2, "fuzz");
    SHANSHUI_CHECK_EQ(fine.columns, h.columns < 2 || h.rows < 2 ? h.columns : 2 * h.columns - 1);
    for (int r = 0; r < fine.rows; ++r) {
      for (int c = 0; c < fine.columns; ++c) {
        const double z = fine.at(c, r);
        if (fine.columns == h.columns) {
          SHANSHUI_CHECK(z == h.at(c, r) || (std::isnan(z) && std::isnan(h.at(c, r))));
          continue;
        }
        const int c0 = c / 2, r0 = r / 2, c1 = std::min(c0 + c % 2, h.columns - 1),
                  r1 = std::min(r0 + r % 2, h.rows - 1);
        const bool hole = std::isnan(h.at(c0, r0)) || std::isnan(h.at(c1, r0)) || std::isnan(h.at(c0, r1)) ||
                          std::isnan(h.at(c1, r1));
        SHANSHUI_CHECK_EQ(std::isnan(z), hole);
        if (c % 2 == 0 && r % 2 == 0 && !hole) SHANSHUI_CHECK(z == h.at(c0, r0));
        if (!hole) SHANSHUI_CHECK(std::isfinite(z));
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace shanshui;
  const fuzz::ScratchFile file(data, size, SHANSHUI_FUZZ_FORMAT);
  fuzz::expectParsedOrRefused([&] {
    terrain::Heightfield h = terrain::loadHeightfield(file.path(), {});
    SHANSHUI_CHECK_EQ(h.elevation.size(), static_cast<std::size_t>(h.columns) * h.rows);
    // A few kilobytes may describe a grid of 10^8 samples (tiles left out are no data): it is
    // loaded and meshed, but smoothing it would take the fuzzer's whole time limit under the
    // sanitizers for work that is only linear (Dequantize's tests check the bands it runs in).
    if (h.elevation.size() <= (std::size_t{1} << 22)) checkSmoothed(h);
    terrain::TerrainMeshOptions options;
    options.max_vertices = 4096;
    (void)terrain::heightfieldToMesh(h, options, nullptr, file.path().string());
  });
  return 0;
}
