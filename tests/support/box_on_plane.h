// A box standing on a plane, lit from one side: a scene whose shadow is known exactly, for
// the shadow pass's test and its resolution bench.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "shanshui/mesh/mesh.h"
#include "shanshui/mesh/shapes.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::test {

struct BoxOnPlane {
  glm::dvec3 light{1.0, 0.5, 1.2};  //!< towards the light
  glm::dvec3 box0{1.5, 1.5, 0.0}, box1{2.3, 2.1, 0.7};

  //! Object 0 the plane, object 1 the box, neither lined nor shaded; an indigo shadow wash
  //! with this softness.
  nlohmann::json scene(double softness) const {
    nlohmann::json j = {{"light", {{"direction", {light.x, light.y, light.z}}}},
                        {"output", {{"fade", 0.0}}},
                        {"shadow", {{"pigment", {{"name", "indigo"}, {"thickness", 1.0}}}, {"softness", softness}}},
                        {"objects", nlohmann::json::array()}};
    for (const char* name : {"plane", "box"})
      j["objects"].push_back({{"mesh", name},
                              {"up", "z"},
                              {"recentre", false},
                              {"lines", {{"enabled", false}}},
                              {"shading", {{"enabled", false}}}});
    j["objects"][1]["transform"] = {{"scale", {box1.x - box0.x, box1.y - box0.y, box1.z - box0.z}},
                                    {"translate", {box0.x, box0.y, box0.z}}};
    return j;
  }

  //! The scene's objects: `plane` (at z = 0) and the unit cube the transform places.
  static std::vector<scene::LoadedObject> load(const scene::Scene& s, const mesh::Mesh& plane) {
    return {{std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(plane, s.objects[0])), nullptr},
            {std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(mesh::unitCube(), s.objects[1])), nullptr}};
  }

  //! Whether world point p lies on the plane and outside the box's footprint.
  bool onPlaneBesideBox(const glm::dvec3& p) const {
    return std::abs(p.z) <= 1e-3 && !(p.x > box0.x && p.x < box1.x && p.y > box0.y && p.y < box1.y);
  }

  //! Whether the ray from p towards the light meets the box (slab test, t > 0).
  bool hidden(const glm::dvec3& p) const {
    const glm::dvec3 l = glm::normalize(light);
    double t0 = 1e-9, t1 = 1e30;
    for (int i = 0; i < 3; ++i) {
      const double a = (box0[i] - p[i]) / l[i], b = (box1[i] - p[i]) / l[i];
      t0 = std::max(t0, std::min(a, b));
      t1 = std::min(t1, std::max(a, b));
    }
    return t0 <= t1;
  }
};

}  // namespace shanshui::test
