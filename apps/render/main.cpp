// shanshui-render: headless (EGL) rendering of a mesh to an image.
#include <cstdio>

#include "shanshui/core/parse.h"
#include "shanshui/image/image_io.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/render/gl_context.h"
#include "shanshui/render/mesh_preview.h"
#include "tool_main.h"

int main(int argc, char** argv) {
  using namespace shanshui;
  CLI::App app{"Renders a mesh headless (EGL, no display needed) to an image.", "shanshui-render"};
  app.footer("Example:\n  shanshui-render out/st_helens.obj -o out/st_helens.png --size 1280x800");
  std::string input, output, size = "1024x768";
  render::PreviewOptions options;
  bool verbose = false;
  app.add_option("input", input, "mesh (.obj, .ply, .off)")->required();
  app.add_option("-o,--output", output, "image to write (.png, .jpg, .tif, .exr)")->required();
  app.add_option("--size", size, "output size WxH")->default_val("1024x768");
  app.add_option("--azimuth", options.azimuth_deg, "camera angle around +Z, degrees")->default_val(-60.0);
  app.add_option("--elevation", options.elevation_deg, "camera angle above the horizon, degrees")->default_val(25.0);
  app.add_option("--zoom", options.zoom, "> 1 moves the camera closer")->default_val(1.0);
  app.add_flag("-v,--verbose", verbose, "print the GL platform");
  return tools::runTool(app, argc, argv, [&] {
    const Size2 s = parseSize(size, "--size");
    options.width = s.width;
    options.height = s.height;
    render::validate(options);
    mesh::RepairReport report;
    const mesh::Mesh m = mesh::repairMesh(mesh::readPolygonSoup(input), {}, &report, input);
    if (report.changed()) std::fprintf(stderr, "note: %s: repaired: %s\n", input.c_str(), report.summary().c_str());
    const auto context = render::GlContext::create({.kind = render::ContextKind::Headless});
    if (verbose) std::fprintf(stderr, "%s\n", context->description().c_str());
    const image::Image img = render::renderPreview(m, options);
    image::saveImage(img, output);
    std::printf("%s\n", output.c_str());
  });
}
