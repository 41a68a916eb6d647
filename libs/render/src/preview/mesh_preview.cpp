#include "shanshui/render/mesh_preview.h"

#include <cmath>
#include <string>
#include <vector>

#include "shanshui/core/error.h"
#include "shanshui/render/gl_check.h"

namespace shanshui::render {

void validate(const PreviewOptions& o) {
  if (o.width < 1 || o.width > 16384 || o.height < 1 || o.height > 16384) {
    throw makeError("--size: ", o.width, "x", o.height, " is out of range; expected 1..16384 per side");
  }
  if (!(o.elevation_deg > -90 && o.elevation_deg < 90)) {
    throw makeError("--elevation: ", o.elevation_deg, " is out of range; expected (-90, 90) degrees");
  }
  if (!std::isfinite(o.azimuth_deg)) throw makeError("--azimuth: must be finite");
  if (!(o.fov_y_deg > 0 && o.fov_y_deg < 180)) {
    throw makeError("--fov: ", o.fov_y_deg, " is out of range; expected (0, 180) degrees");
  }
  if (!(o.zoom > 0 && o.zoom <= 1000)) throw makeError("zoom: ", o.zoom, " is out of range; expected (0, 1000]");
  if (!(glm::length(o.light_dir) > 0)) throw makeError("light direction must be non-zero");
  if (!(o.checker_squares >= 0 && o.checker_squares <= 1e6)) {
    throw makeError("checker squares: ", o.checker_squares, " is out of range; expected [0, 1e6]");
  }
}

MeshPreview::MeshPreview(const mesh::Mesh& m, bool checker)
    : bounds_(mesh::bounds(m)),
      checker_(checker),
      program_({"mesh_preview.vert", "mesh_preview.frag"},
               checker ? std::vector<std::string>{"CHECKER"} : std::vector<std::string>{}),
      gpu_(m, bounds_.centre()) {
  if (checker && m.uvs.size() != m.positions.size()) throw makeError("checker view: the mesh has no UVs");
}

void MeshPreview::render(const Framebuffer& target, const PreviewOptions& o) const {
  validate(o);
  const double aspect = static_cast<double>(target.width()) / target.height();
  const OrbitCamera camera = frameBounds(bounds_, o.azimuth_deg, o.elevation_deg, o.fov_y_deg, aspect, o.zoom);
  target.bind();
  glClearColor(o.paper.r, o.paper.g, o.paper.b, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  program_.use();
  program_.set("u_view_projection", camera.projection(aspect) * camera.view());
  program_.set("u_eye", glm::vec3(camera.eye()));
  program_.set("u_light_dir", glm::normalize(o.light_dir));
  program_.set("u_paper", o.paper);
  program_.set("u_ink", o.ink);
  program_.set("u_rim_width", o.rim_width);
  if (checker_) program_.set("u_checker_squares", o.checker_squares);
  gpu_.draw();
  SHANSHUI_GL_CHECK("mesh preview");
}

image::Image renderPreview(const mesh::Mesh& m, const PreviewOptions& options) {
  validate(options);
  const MeshPreview preview(m, options.checker_squares > 0.0f);
  const Framebuffer fb(options.width, options.height, {GL_RGBA8}, true);
  preview.render(fb, options);
  glFinish();
  return fb.colour(0).download(3);
}

}  // namespace shanshui::render
