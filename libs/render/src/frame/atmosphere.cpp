#include "frame/atmosphere.h"

#include <algorithm>
#include <limits>

#include "shanshui/scene/grounding.h"

namespace shanshui::render {

namespace {
double smooth01(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
}  // namespace

glm::dvec2 fadeRange(const FrameInputs& in) {
  const glm::dvec3 eye = in.camera.eye();
  glm::dvec2 range(1e300, 0.0);
  for (int c = 0; c < 8; ++c) {
    const double d = glm::length(in.world_bounds.corner(c) - eye);
    range = {std::min(range.x, d), std::max(range.y, d)};
  }
  return range;
}

double presence(const FrameInputs& in, std::size_t object, const glm::dmat4& to_model, glm::dvec3 world,
                glm::dvec2 fade_range) {
  const scene::Scene& s = in.scene;
  const double far =
      smooth01((glm::length(world - in.camera.eye()) - fade_range.x) / std::max(fade_range.y - fade_range.x, 1e-9));
  double f = 1.0 - s.output.fade * far;
  if (s.mist.enabled()) {
    const double z0 = in.world_bounds.min.z, extent = std::max(in.world_bounds.size().z, 1e-9);
    const double h0 = (world.z - (z0 + s.mist.height * extent)) / std::max(s.mist.softness * extent, 1e-9);
    const double share = s.mist.near + (1.0 - s.mist.near) * far;
    f *= 1.0 - s.mist.density * share * (1.0 - smooth01(h0));
  }
  const scene::Object& o = s.objects[object];
  if (o.dissolvesBorder()) {
    const glm::dvec3 m = glm::dvec3(to_model * glm::dvec4(world, 1.0));
    const glm::dvec3 half = 0.5 * in.objects[object].model_bounds.size();
    const double width = o.border.width * std::min(half.x, half.y);
    const double t = std::min(half.x - std::abs(m.x), half.y - std::abs(m.y)) / std::max(width, 1e-12);
    f *= smooth01(t - 0.5 * o.border.roughness);
  }
  return std::clamp(f, 0.0, 1.0);
}

float waterLevel(const FrameInputs& in) {
  if (!in.scene.usesWater()) return std::numeric_limits<float>::lowest();
  return static_cast<float>(scene::waterHeight(in.scene, in.world_bounds));
}

glm::vec3 pictureHorizontal(const FrameInputs& in) {
  const glm::mat4 v = in.camera.view();
  glm::dvec3 r(v[0][0], v[1][0], 0.0);
  if (glm::length(r) < 1e-9) r = {1.0, 0.0, 0.0};
  return glm::vec3(glm::normalize(r));
}

}  // namespace shanshui::render
