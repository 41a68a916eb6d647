// The renderer's passes, in execution order: the one place a pass is added.
#include <glm/gtc/matrix_transform.hpp>

#include "shanshui/render/render_pass.h"

namespace shanshui::render {

namespace {
bool always(const scene::Scene&) {
  return true;
}
bool hasCanvas(const scene::Scene& s) {
  return s.canvas.type != scene::CanvasType::None;
}
bool brushStrokes(const scene::Scene& s) {
  return s.usesBrushStrokes();
}
bool pigmented(const scene::Scene& s) {
  return s.usesPigment();
}
bool shadowed(const scene::Scene& s) {
  return s.usesShadow();
}
bool onPaperRelief(const scene::Scene& s) {
  return s.substrate.enabled;
}
bool edgesDarken(const scene::Scene& s) {
  return s.edges.enabled;
}
bool blursMotion(const scene::Scene& s) {
  return s.motion_blur.enabled;
}
bool growsElements(const scene::Scene& s) {
  return s.usesElements();
}
bool diffuses(const scene::Scene& s) {
  return s.diffusion.enabled();
}
std::string nothing(const scene::Scene&) {
  return "";
}
}  // namespace

const std::vector<PassEntry>& passList() {
  static const std::vector<PassEntry> list = {
      {"gbuffer", always, gbufferStructure, makeGbufferPass},
      {"canvas", hasCanvas, canvasStructure, makeCanvasPass},
      {"elements", growsElements, elementsStructure, makeElementsPass},
      {"ink", always, inkStructure, makeInkPass},
      {"strokes", brushStrokes, strokesStructure, makeStrokesPass},
      {"pigment", pigmented, nothing, makePigmentPass},
      {"shadow", shadowed, nothing, makeShadowPass},
      {"edges", edgesDarken, edgesStructure, makeEdgesPass},
      {"diffusion", diffuses, nothing, makeDiffusionPass},
      {"motion_blur", blursMotion, nothing, makeMotionBlurPass},
      {"substrate", onPaperRelief, nothing, makeSubstratePass},
  };
  return list;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

glm::dmat4 FrameInputs::modelAt(std::size_t i, double t) const {
  // A spinning object turns about the vertical axis through its centre (the origin of its
  // uploaded coordinates); a moving one is carried by its velocity and along its path.
  const scene::Object& o = scene.objects[i];
  const glm::dmat4& model = objects[i].model;
  if (!o.animated()) return model;
  return glm::translate(glm::dmat4(1.0), o.velocity * t + o.pathOffset(t)) *
         glm::rotate(model, glm::radians(o.spin_deg_per_s * t), glm::dvec3(0, 0, 1));
}

glm::mat4 FrameInputs::viewProjection() const {
  return camera.projection(static_cast<double>(width) / height) * camera.view();
}

glm::dmat4 FrameInputs::previousViewProjection() const {
  const OrbitCamera& c = previous_camera ? *previous_camera : camera;
  return glm::dmat4(c.projection(static_cast<double>(width) / height)) * glm::dmat4(c.view());
}

}  // namespace shanshui::render
