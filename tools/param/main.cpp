// shanshui-param: UVs for a mountain mesh so the wrinkle texture maps without stretch.
#include <algorithm>
#include <cmath>
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
      "Computes UVs for a mesh (SPEC.md section 5) after repairing it: planar projection,\n"
      "one of CGAL's parameterizers, or an atlas of charts for closed meshes, handles and\n"
      "several components; validated (finite, no flipped or zero-area UV faces) and measured\n"
      "(Sander L2/Linf stretch, angle and area distortion). auto tries what fits in --budget\n"
      "and keeps the least stretch; a map above --max-stretch is an error.",
      "shanshui-param"};
  app.footer(
      "Example:\n  shanshui-param out/mountain.obj -o out/mountain_uv.obj --texel-size 200 "
      "--report out/param.json --checker out/checker.png\n"
      "  shanshui-param cow.off -o cow_uv.obj --method charts --padding 4 --checker cow.png");
  std::string input, output, methodName = "auto", borderName = "circle", reportPath, checkerPath, components;
  double texelSize = 0.0;
  bool normalize = false;
  param::ParamOptions options;
  app.add_option("input", input,
                 "mesh (.obj, .ply, .off, .gltf, .glb, .fbx, .dae, .3ds, .stl, or any format Assimp reads)")
      ->required();
  app.add_option("-o,--output", output, "mesh with UVs (.obj keeps them; .ply/.off do not)")->required();
  app.add_option("--method", methodName, "auto|xy|mvc|dcm|tutte|lscm|arap|authalic|charts")->default_val("auto");
  app.add_option("--budget", options.budget_seconds, "auto: seconds to spend trying methods (the first always runs)")
      ->default_val(options.budget_seconds)
      ->check(CLI::NonNegativeNumber);
  app.add_option("--max-stretch", options.max_stretch, "fail when the kept map's L2 stretch is above this")
      ->default_val(options.max_stretch)
      ->check(CLI::Range(1.0, 1e300));
  app.add_flag("--accept-stretch", options.accept_over_stretch, "keep the best map even above --max-stretch");
  bool noRefine = false;
  app.add_flag("--no-refine", noRefine,
               "auto: keep the methods' maps as they are (no ARAP rounds from the best one with the budget left)");
  app.add_option("--padding", options.charts.padding_texels, "charts: texels between charts in the atlas")
      ->default_val(options.charts.padding_texels)
      ->check(CLI::Range(0.0, 64.0));
  app.add_option("--atlas-resolution", options.charts.atlas_resolution,
                 "charts: texels along the atlas's longer side, for --padding")
      ->default_val(options.charts.atlas_resolution)
      ->check(CLI::Range(64, 16384));
  app.add_option("--chart-stretch", options.charts.max_chart_stretch,
                 "charts: split a chart again when its own L2 stretch is above this")
      ->default_val(options.charts.max_chart_stretch)
      ->check(CLI::Range(1.0, 1e300));
  app.add_option("--chart-fill", options.charts.min_fill,
                 "charts: cut a chart that fills less than this of its bounding rectangle")
      ->default_val(options.charts.min_fill)
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--border", borderName, "circle|square, for mvc, dcm, tutte, authalic")->default_val("circle");
  auto* texel = app.add_option("--texel-size", texelSize, "world size covered by one texture repeat (mesh units)");
  app.add_flag("--normalize", normalize, "scale UVs into [0,1] (the default when --texel-size is absent)")
      ->excludes(texel);
  app.add_option("--components", components,
                 "connected components: keep-all (default for auto and charts), keep-largest (with a warning; "
                 "default for the one-piece methods) or fail")
      ->check(CLI::IsMember({"keep-all", "keep-largest", "fail"}));
  app.add_option("--report", reportPath, "write distortion, timings and repairs as JSON");
  app.add_option("--checker", checkerPath, "render a checkerboard-textured view of the result (PNG)");
  return tools::runBatchableTool(app, argc, argv, [&] {
    options.method = param::parseMethod(methodName);
    options.refine = !noRefine;
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
    if (texel->count() > 0) {  // UVs are mesh units over the texel size: they must fit a float
      const mesh::Bounds b = mesh::bounds(soup.positions);
      const double extent = std::max({b.size().x, b.size().y, b.size().z});
      if (!(extent / texelSize < 1e37)) {
        throw makeError("--texel-size: ", texelSize, " makes UVs beyond a float's range on a mesh ", extent,
                        " units across; expected at least ", extent / 1e37);
      }
    }
    mesh::RepairOptions repairOptions;
    const bool atlasAllowed = options.method == param::Method::Auto || options.method == param::Method::Charts;
    if (components.empty()) components = atlasAllowed ? "keep-all" : "keep-largest";
    repairOptions.components = components == "fail"           ? mesh::ComponentPolicy::Fail
                               : components == "keep-largest" ? mesh::ComponentPolicy::KeepLargest
                                                              : mesh::ComponentPolicy::KeepAll;
    repairOptions.max_hole_edges = 1 << 30;  // every hole except the outer border must be filled
    mesh::RepairReport repair;
    mesh::Mesh m = mesh::repairMesh(soup, repairOptions, &repair, input);
    for (const auto& w : repair.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    if (repair.changed()) std::fprintf(stderr, "%s: repaired: %s\n", input.c_str(), repair.summary().c_str());

    param::ParamReport report;
    m = param::parameterize(m, options, &report, input);
    if (options.method == param::Method::Auto) {
      std::fprintf(stderr, "%s: auto tried (budget %.3g s):\n%s  kept %s\n", input.c_str(), options.budget_seconds,
                   param::trialTable(report).c_str(), report.decision.c_str());
    }
    if (report.method == param::Method::Charts) {
      std::fprintf(stderr,
                   "%s: atlas of %zu charts (%d split after flattening, %d merged back), %.0f%% of the atlas used\n",
                   input.c_str(), report.atlas.charts.size(), report.atlas.splits, report.atlas.merges,
                   100.0 * report.atlas.usage);
    }
    if (report.seam_vertices > 0) {
      std::fprintf(stderr, "%s: closed mesh cut open along a seam of %d vertices\n", input.c_str(),
                   report.seam_vertices);
    }
    if (texel->count() > 0) {
      param::scaleToTexelSize(m, texelSize);
      if (!std::all_of(m.uvs.begin(), m.uvs.end(),
                       [](const glm::vec2& uv) { return std::isfinite(uv.x) && std::isfinite(uv.y); })) {
        throw makeError("--texel-size: ", texelSize, " makes UVs beyond a float's range");
      }
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
      j["budget_seconds"] = options.budget_seconds;
      j["max_stretch"] = options.max_stretch;
      j["decision"] = report.decision;
      j["seam_vertices"] = report.seam_vertices;
      j["vertices"] = m.vertexCount();
      j["faces"] = m.triangleCount();
      j["distortion"] = distortionJson(report.distortion);
      j["valid"] = report.distortion.valid();
      for (const param::MethodTrial& t : report.trials) {
        nlohmann::json tj{{"method", param::methodName(t.method)},
                          {"ran", t.ran},
                          {"seconds", t.seconds},
                          {"predicted_seconds", t.predicted_seconds}};
        if (t.ran) tj["distortion"] = distortionJson(t.distortion);
        if (!t.note.empty()) tj["note"] = t.note;
        j["trials"].push_back(tj);
      }
      for (const param::Refinement& f : report.refinements) {
        j["refinements"].push_back({{"from", param::methodName(f.from)},
                                    {"seconds", f.seconds},
                                    {"rounds", f.rounds},
                                    {"converged", f.converged},
                                    {"good_enough", f.enough},
                                    {"kept", f.kept},
                                    {"distortion", distortionJson(f.distortion)}});
      }
      if (report.method == param::Method::Charts) {
        const param::AtlasReport& a = report.atlas;
        nlohmann::json aj{{"charts", a.charts.size()},
                          {"usage", a.usage},
                          {"splits", a.splits},
                          {"merges", a.merges},
                          {"padding_texels", options.charts.padding_texels},
                          {"resolution", options.charts.atlas_resolution}};
        for (const param::ChartReport& c : a.charts) {
          aj["per_chart"].push_back({{"faces", c.faces},
                                     {"area", c.area},
                                     {"method", c.method},
                                     {"distortion", distortionJson(c.distortion)}});
        }
        j["atlas"] = aj;
      }
      j["uv_scale"] = texel->count() > 0 ? nlohmann::json{{"texel_size", texelSize}} : nlohmann::json("normalized");
      for (const auto& [name, value] : repair.counters()) j["repair"][name] = value;
      j["repair_warnings"] = repair.warnings;
      outputs.stage(reportPath, tools::jsonText(j, reportPath));
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
