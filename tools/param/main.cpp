// shanshui-param: UVs for a mountain mesh so the wrinkle texture maps without stretch.
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "json_text.h"
#include "shanshui/core/atomic_output.h"
#include "shanshui/image/image_io.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/param/parameterize.h"
#include "shanshui/param/uv_adjust.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/mesh_preview.h"
#include "tool_main.h"

namespace {

using namespace shanshui;

nlohmann::json distortionJson(const param::Distortion& d) {
  return {{"l2_stretch", d.l2_stretch},
          {"linf_stretch", d.linf_stretch},
          {"angle_distortion", d.angle_distortion},
          {"area_distortion", d.area_distortion},
          {"faces", d.faces},
          {"flipped", d.flipped},
          {"degenerate", d.degenerate},
          {"non_finite", d.non_finite},
          {"valid", d.valid()}};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Computes UVs for a mesh (SPEC.md section 5) after repairing it: planar projection or\n"
      "one of CGAL's parameterizers, validated (finite, no flipped or zero-area UV faces)\n"
      "and measured (Sander L2/Linf stretch, angle and area distortion).",
      "shanshui-param"};
  app.footer(
      "Example:\n  shanshui-param out/mountain.obj -o out/mountain_uv.obj --texel-size 200 "
      "--report out/param.json --checker out/checker.png");
  std::string input, output, methodName = "auto", borderName = "circle", reportPath, checkerPath,
                             components = "keep-largest";
  double texelSize = 0.0;
  bool normalize = false;
  app.add_option("input", input, "mesh (.obj, .ply, .off)")->required();
  app.add_option("-o,--output", output, "mesh with UVs (.obj keeps them; .ply/.off do not)")->required();
  app.add_option("--method", methodName, "auto|xy|mvc|dcm|tutte|lscm|arap|authalic")->default_val("auto");
  app.add_option("--border", borderName, "circle|square, for mvc, dcm, tutte, authalic")->default_val("circle");
  auto* texel = app.add_option("--texel-size", texelSize, "world size covered by one texture repeat (mesh units)");
  app.add_flag("--normalize", normalize, "scale UVs into [0,1] (the default when --texel-size is absent)")
      ->excludes(texel);
  app.add_option("--components", components, "extra connected components: keep-largest (with a warning) or fail")
      ->check(CLI::IsMember({"keep-largest", "fail"}))
      ->default_val("keep-largest");
  app.add_option("--report", reportPath, "write distortion, timings and repairs as JSON");
  app.add_option("--checker", checkerPath, "render a checkerboard-textured view of the result (PNG)");
  return tools::runBatchableTool(app, argc, argv, [&] {
    param::ParamOptions options;
    options.method = param::parseMethod(methodName);
    options.border = param::parseBorder(borderName);
    OutputSet outputs({input});
    if (!output.ends_with(".obj")) throw makeError(output, ": UVs are only written to .obj files");
    outputs.declare(output, "-o", {".obj"});
    if (!reportPath.empty()) outputs.declare(reportPath, "--report", {".json"});
    if (!checkerPath.empty()) outputs.declare(checkerPath, "--checker", image::writableImageExtensions());
    if (texel->count() > 0 && !(texelSize > 0)) {
      throw makeError("--texel-size: ", texelSize, "; expected a positive length in mesh units");
    }

    const mesh::PolygonSoup soup = mesh::readPolygonSoup(input);
    mesh::RepairOptions repairOptions;
    repairOptions.components = components == "fail" ? mesh::ComponentPolicy::Fail : mesh::ComponentPolicy::KeepLargest;
    repairOptions.max_hole_edges = 1 << 30;  // every hole except the outer border must be filled
    mesh::RepairReport repair;
    mesh::Mesh m = mesh::repairMesh(soup, repairOptions, &repair, input);
    for (const auto& w : repair.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (repair.changed()) std::fprintf(stderr, "%s: repaired: %s\n", input.c_str(), repair.summary().c_str());

    param::ParamReport report;
    m = param::parameterize(m, options, &report, input);
    if (report.seam_vertices > 0) {
      std::fprintf(stderr, "%s: closed mesh cut open along a seam of %d vertices\n", input.c_str(),
                   report.seam_vertices);
    }
    if (texel->count() > 0) {
      param::scaleToTexelSize(m, texelSize);
    } else {
      param::normalizeUvs(m);
    }
    outputs.stage(output, mesh::encodeMesh(m, output));
    std::fprintf(stderr, "%s: %s in %.2f s: %s\n", output.c_str(), param::methodName(report.method), report.seconds,
                 report.distortion.summary().c_str());

    if (!reportPath.empty()) {
      nlohmann::json j;
      j["input"] = input;
      j["output"] = output;
      j["method"] = param::methodName(report.method);
      j["requested_method"] = methodName;
      j["border"] = borderName;
      j["seconds"] = report.seconds;
      j["seam_vertices"] = report.seam_vertices;
      j["vertices"] = m.vertexCount();
      j["faces"] = m.triangleCount();
      j["distortion"] = distortionJson(report.distortion);
      j["valid"] = report.distortion.valid();
      for (const param::MethodTrial& t : report.trials) {
        nlohmann::json tj{{"method", param::methodName(t.method)}, {"ran", t.ran}, {"seconds", t.seconds}};
        if (t.ran) tj["distortion"] = distortionJson(t.distortion);
        if (!t.note.empty()) tj["note"] = t.note;
        j["trials"].push_back(tj);
      }
      j["uv_scale"] = texel->count() > 0 ? nlohmann::json{{"texel_size", texelSize}} : nlohmann::json("normalized");
      for (const auto& [name, value] : repair.counters()) j["repair"][name] = value;
      j["repair_warnings"] = repair.warnings;
      outputs.stage(reportPath, tools::jsonText(j));
    }
    if (!checkerPath.empty()) {
      const auto context = render::GlContext::create({});
      render::PreviewOptions view;
      view.width = 1024;
      view.height = 768;
      view.elevation_deg = 35.0;
      view.zoom = 1.6;
      view.checker_squares = texel->count() > 0 ? 2.0f : 16.0f;
      outputs.stage(checkerPath, image::encodeImage(render::renderPreview(m, view), checkerPath));
    }
    outputs.commit();
  });
}
