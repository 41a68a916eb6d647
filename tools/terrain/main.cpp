// shanshui-terrain: DEM or height map to a mountain mesh.
#include <cstdio>

#include "shanshui/core/atomic_output.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/terrain/terrain_mesh.h"
#include "tool_main.h"

int main(int argc, char** argv) {
  using namespace shanshui;
  CLI::App app{
      "Turns a DEM or height map into a triangle mesh (x east, y north, z up, metres).\n"
      "Inputs: 8/16-bit PNG or TIFF height maps, USGS ASCII DEM (.dem), ESRI ASCII grid (.asc).",
      "shanshui-terrain"};
  app.footer(
      "Example:\n  shanshui-terrain samples/terrain/mount_st_helens.dem -o out/st_helens.obj --max-vertices 100000");
  std::string input, output;
  terrain::HeightfieldOptions field;
  terrain::TerrainMeshOptions meshOptions;
  app.add_option("input", input, "height map or DEM")->required();
  app.add_option("-o,--output", output, "mesh to write (.obj, .ply or .off)")->required();
  app.add_option("--cell-size", field.cell_size, "metres between samples; default: from the file (1 m for images)");
  app.add_option("--z-scale", meshOptions.z_scale, "vertical exaggeration")->default_val(1.0);
  app.add_option("--step", meshOptions.step, "keep every N-th sample")
      ->check(tools::integerIn(1, 1000000))
      ->default_val(1);
  app.add_option("--max-vertices", meshOptions.max_vertices,
                 "raise the step until the grid has at most K vertices (0: no limit)")
      ->check(tools::integerIn(0, 2000000000))
      ->default_val(0);
  return tools::runBatchableTool(app, argc, argv, [&] {
    if (field.cell_size < 0 || (app.count("--cell-size") && field.cell_size == 0)) {
      throw makeError("--cell-size: ", field.cell_size, " is out of range; expected (0, 1e6] metres");
    }
    terrain::validate(meshOptions);
    OutputSet outputs({input});
    outputs.declare(output, "-o", {".obj", ".ply", ".off"});
    const terrain::Heightfield h = terrain::loadHeightfield(input, field);
    const auto [lo, hi] = h.elevationRange();
    std::fprintf(stderr, "%s; cells %.3f x %.3f m; elevations %.1f to %.1f m; %zu of %zu samples valid\n",
                 h.source.c_str(), h.cell_x, h.cell_y, lo, hi, h.validCount(), h.elevation.size());
    for (const auto& note : h.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    terrain::TerrainMeshInfo info;
    const mesh::Mesh m = terrain::heightfieldToMesh(h, meshOptions, &info, input);
    outputs.stage(output, mesh::encodeMesh(m, output));
    outputs.commit();
    std::fprintf(stderr, "wrote %s: %zu vertices, %zu triangles (step %d, x/y offset %.3f %.3f removed)\n",
                 output.c_str(), m.vertexCount(), m.triangleCount(), info.step, info.offset.x, info.offset.y);
  });
}
