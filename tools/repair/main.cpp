// shanshui-repair: clean a mesh for rendering and parameterization, and say what changed.
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "tool_main.h"

int main(int argc, char** argv) {
  using namespace shanshui;
  CLI::App app{
      "Repairs a mesh (SPEC.md section 4): drops NaN vertices and invalid faces, merges\n"
      "duplicates, orients, splits non-manifold vertices, triangulates, removes degenerate\n"
      "faces and extra components, fills holes; reports what it changed.",
      "shanshui-repair"};
  app.footer(
      "Examples:\n  shanshui-repair broken.off -o fixed.obj --report repair.json\n"
      "  shanshui-repair lowpoly_land.glb -o land.obj --subdivide 2");
  std::string input, output, reportPath, components = "keep-largest";
  mesh::RepairOptions options;
  bool noFill = false;
  app.add_option("input", input,
                 "mesh to repair (.obj, .ply, .off, .gltf, .glb, .fbx, .dae, .3ds, .stl, or any format Assimp reads)")
      ->required();
  app.add_option("-o,--output", output, "repaired mesh (.obj, .ply, .off)")->required();
  app.add_option("--components", components, "extra connected components")
      ->check(CLI::IsMember({"keep-largest", "fail", "keep-all"}))
      ->default_val("keep-largest");
  app.add_flag("--no-fill-holes", noFill, "leave holes open");
  app.add_option("--max-hole-edges", options.max_hole_edges, "larger holes stay open")
      ->check(tools::integerIn(0, 2000000000))
      ->default_val(1000);
  app.add_option("--report", reportPath, "write what was changed as JSON");
  int subdivide = 0;
  app.add_option("--subdivide", subdivide,
                 "then N steps of Loop subdivision (0-4), each making four triangles of one and rounding the "
                 "surface: a low-poly land drawn as rounded ground (UVs are dropped)")
      ->check(tools::integerIn(0, mesh::kMostSubdivisions))
      ->default_val(0);
  return tools::runBatchableTool(app, argc, argv, [&] {
    options.fill_holes = !noFill;
    options.components = components == "fail"       ? mesh::ComponentPolicy::Fail
                         : components == "keep-all" ? mesh::ComponentPolicy::KeepAll
                                                    : mesh::ComponentPolicy::KeepLargest;
    OutputSet outputs({input});
    outputs.declare(output, "-o", {".obj", ".ply", ".off"});
    if (!reportPath.empty()) outputs.declare(reportPath, "--report", {".json"});
    const mesh::PolygonSoup soup = mesh::readPolygonSoup(input);
    mesh::RepairReport report;
    const mesh::Mesh m = mesh::subdivideLoop(mesh::repairMesh(soup, options, &report, input), subdivide, input);
    outputs.stage(output, mesh::encodeMesh(m, output));
    if (!reportPath.empty()) {
      nlohmann::json j;
      j["input"] = input;
      j["output"] = output;
      j["input_vertices"] = report.input_vertices;
      j["input_faces"] = report.input_faces;
      j["output_vertices"] = report.output_vertices;
      j["output_faces"] = report.output_faces;
      for (const auto& [name, value] : report.counters()) j["changes"][name] = value;
      j["attributes_dropped"] = report.attributes_dropped;
      j["warnings"] = report.warnings;
      if (subdivide > 0) {
        j["subdivided"] = {{"steps", subdivide}, {"vertices", m.positions.size()}, {"faces", m.triangles.size()}};
      }
      outputs.stage(reportPath, tools::jsonText(j, reportPath));
    }
    outputs.commit();
    for (const auto& n : soup.notes) std::fprintf(stderr, "note: %s\n", n.c_str());
    for (const auto& w : report.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    std::fprintf(stderr, "%s: %s\n", input.c_str(), report.summary().c_str());
  });
}
