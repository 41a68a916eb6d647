// Scenes around meshes held in memory, for renderer tests: the mesh file name is never read.
#pragma once

#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "shanshui/mesh/mesh.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::test {

//! A one-object scene: `object_overrides` merged into the object, `top` the rest of the scene.
inline scene::Scene sceneWith(const nlohmann::json& object_overrides,
                              const nlohmann::json& top = nlohmann::json::object()) {
  nlohmann::json j = top;
  nlohmann::json o = {{"mesh", "memory.obj"}};
  if (object_overrides.is_object()) o.update(object_overrides, true);
  j["objects"] = nlohmann::json::array({o});
  return scene::parseScene(j, "test", ".");
}

//! The loaded object of a one-object scene, from `m` (and a wrinkle texture, if any).
inline std::vector<scene::LoadedObject> prepare(const scene::Scene& s, const mesh::Mesh& m,
                                                std::shared_ptr<const image::Image> wrinkle = nullptr) {
  return {{std::make_shared<const scene::ObjectAsset>(scene::prepareAsset(m, s.objects[0])), std::move(wrinkle)}};
}

}  // namespace shanshui::test
