// shanshui-terrain: DEM or height map to a mountain mesh.
#include <cstdio>

#include "shanshui/core/atomic_output.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"
#include "tool_main.h"

int main(int argc, char** argv) {
  using namespace shanshui;
  CLI::App app{
      "Turns a DEM or height map into a triangle mesh (x east, y north, z up, metres).\n"
      "Inputs: every raster GDAL reads (GeoTIFF of any sample type, COG, BigTIFF, SRTM .hgt, VRT, .img, ...;\n"
      "cell size, units and no-data from the georeference), PNG or TIFF height maps without one (the cell size\n"
      "it used is printed), USGS ASCII DEM (.dem), ESRI ASCII grid (.asc).",
      "shanshui-terrain"};
  app.footer(
      "Examples:\n  shanshui-terrain samples/terrain/mount_st_helens.dem -o out/st_helens.obj --max-vertices 100000\n"
      "  shanshui-terrain samples/terrain/hill_utm.tif -o hill.obj\n"
      "  shanshui-terrain N46E007.hgt -o alps.ply --max-vertices 250000 --fill-nodata\n"
      "  shanshui-terrain coast_gebco.asc -o coast.obj --upsample 4");
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
  std::vector<double> crop;
  app.add_option("--crop", crop,
                 "keep the part W S E N of the grid, fractions of its width and height (x east, y north)")
      ->expected(4);
  app.add_flag("--fill-nodata", field.fill_nodata,
               "fill no-data samples (voids, the sea) by interpolation instead of leaving holes");
  bool smooth_steps = false;
  app.add_flag("--smooth-steps", smooth_steps,
               "smooth heights stored in steps (whole metres, tenths, grey levels) within half a step, as the "
               "renderer does when it loads a DEM, so gentle ground is not meshed as a staircase of cracks");
  int upsample = 1;
  app.add_option("--upsample", upsample,
                 "make the grid N times finer along each side by bicubic interpolation (1-8; every stored sample "
                 "keeps its height), so a coarse DEM's coasts and ridges are curves, not the grid's facets")
      ->check(tools::integerIn(1, terrain::kMostUpsample))
      ->default_val(1);
  return tools::runBatchableTool(app, argc, argv, [&] {
    if (field.cell_size < 0 || (app.count("--cell-size") && field.cell_size == 0)) {
      throw makeError("--cell-size: ", field.cell_size, " is out of range; expected (0, 1e6] metres");
    }
    terrain::validate(meshOptions);
    OutputSet outputs({input});
    outputs.declare(output, "-o", {".obj", ".ply", ".off"});
    if (!crop.empty()) std::copy(crop.begin(), crop.end(), field.crop.begin());
    // A large raster is read decimated to the vertex budget (GDAL formats) instead of whole.
    field.max_samples = meshOptions.max_vertices;
    terrain::Heightfield h = terrain::loadHeightfield(input, field);
    const auto [lo, hi] = h.elevationRange();
    std::fprintf(stderr, "%s; cells %.3f x %.3f m; elevations %.1f to %.1f m; %zu of %zu samples valid\n",
                 h.source.c_str(), h.cell_x, h.cell_y, lo, hi, h.validCount(), h.elevation.size());
    if (smooth_steps) terrain::dequantize(h);
    terrain::upsample(h, upsample, "--upsample");
    for (const auto& note : h.notes) std::fprintf(stderr, "note: %s\n", note.c_str());
    terrain::TerrainMeshInfo info;
    const mesh::Mesh m = terrain::heightfieldToMesh(h, meshOptions, &info, input);
    outputs.stage(output, mesh::encodeMesh(m, output));
    outputs.commit();
    std::fprintf(stderr, "wrote %s: %zu vertices, %zu triangles (step %d, x/y offset %.3f %.3f removed)\n",
                 output.c_str(), m.vertexCount(), m.triangleCount(), info.step, info.offset.x, info.offset.y);
  });
}
