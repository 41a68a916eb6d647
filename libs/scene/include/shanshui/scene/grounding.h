// Objects standing on other objects (objects.N.ground, issue 45): a hut, a pavilion, a
// pagoda, a boulder on a terrain. Each grounded object's world matrix is its transform's,
// moved so its base rests on the ground's surface under it, at the spot its transform gives
// or one found from the ground's form (a summit, a ridge's crest, the water's edge, a bank,
// the foot of a slope). Resolved on the CPU whenever the renderer takes the scene's keys, so
// the viewer's live changes move it; a scene with no grounded object builds nothing here.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shanshui/elements/placement.h"
#include "shanshui/mesh/mesh.h"
#include "shanshui/scene/scene.h"
#include "shanshui/scene/scene_assets.h"

namespace shanshui::scene {

//! objects.N.ground.on naming no object but this floats the object on the water.
inline constexpr const char* kOnWater = "water";

//! objects[i] floats on the water (ground.on "water", the scene has water and no object of
//! that name).
bool floatsOnWater(const Scene& s, std::size_t i);

//! The index of the object objects[i] stands on (by name), or nothing when it is not grounded
//! or the name matches no other object.
std::optional<std::size_t> groundOf(const Scene& s, std::size_t i);

//! What is wrong with the scene's grounding (a name that matches no object or several, an
//! object on itself, on a grounded or moving object), or empty.
std::string groundingProblem(const Scene& s);

//! World bounds of the objects that stand on nothing: the terrain's extent, from which the
//! water level, the mist's height and the fade are measured (a pagoda on a summit must not
//! move them).
mesh::Bounds baseBounds(const Scene& s, const std::vector<mesh::Bounds>& model_bounds);

//! The water's surface height, world z, for bounds from baseBounds (lowest float without water).
double waterHeight(const Scene& s, const mesh::Bounds& base);

class Grounding {
 public:
  //! Keeps the objects' geometry (shared, not copied) to look their ground up.
  explicit Grounding(const std::vector<LoadedObject>& objects);

  //! Every object's model-to-world matrix for the scene's keys: the transform's, and for a
  //! grounded object the pose that rests it on its ground. Throws Error naming the object's
  //! key for a spot off its ground, a tilted ground, or a rule that finds no spot.
  std::vector<glm::dmat4> worldMatrices(const Scene& s) const;

 private:
  const elements::Terrain& terrain(std::size_t ground) const;
  std::vector<std::shared_ptr<const ObjectAsset>> geometry_;
  mutable std::map<std::size_t, std::unique_ptr<elements::Terrain>> terrains_;
};

//! True when some object of the scene is grounded (the renderer builds a Grounding then).
bool usesGrounding(const Scene& s);

}  // namespace shanshui::scene
