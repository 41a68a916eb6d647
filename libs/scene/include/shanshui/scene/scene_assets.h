// What a scene's objects need on the GPU, loaded (and meshed, repaired, measured) on the
// CPU: meshes with the attributes the scene's passes use, curvature, wrinkle images.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "shanshui/elements/placement.h"
#include "shanshui/image/image.h"
#include "shanshui/mesh/mesh.h"
#include "shanshui/scene/scene.h"

namespace shanshui::terrain {
struct Heightfield;  // heightfield.h (the terrain library is the scene library's own)
struct HeightfieldOptions;
}  // namespace shanshui::terrain

namespace shanshui::scene {

struct ObjectAsset {
  mesh::Mesh mesh;      //!< model space (recentred when the object asks); UVs when wrinkled
  mesh::Bounds bounds;  //!< of mesh
  //! Per-vertex |k|·feature_size (dimensionless, 1 at the 90th percentile); empty unless
  //! the object draws lines from object-space curvature.
  std::vector<float> curvature;
  double feature_size = 0.0;  //!< 1 / (90th percentile of |k|), model units; 0 if not measured
  double load_seconds = 0.0;
};

//! Elements grown on an object (trees, moss dots), in its model coordinates.
struct ElementSet {
  std::vector<elements::Instance> instances;
  double place_seconds = 0.0;
};

//! One object's geometry, its wrinkle image (one channel, Eq. 5's luma; null without) and
//! the elements grown on it (null when it grows none).
struct LoadedObject {
  std::shared_ptr<const ObjectAsset> geometry;
  std::shared_ptr<const image::Image> wrinkle;
  std::shared_ptr<const ElementSet> elements = nullptr;
};

//! Keeps loaded assets by what they were made from, so a viewer that changes a parameter
//! does not reload meshes, and one that changes a file path loads only that file.
class AssetCache {
 public:
  //! Loads (or reuses) what scene.objects[index] needs. Throws Error naming the scene key
  //! and the file for unreadable input, or a wrinkled object without UVs.
  LoadedObject get(const Scene& scene, std::size_t index);
  std::vector<LoadedObject> getAll(const Scene& scene);

  //! A file already read (loadSceneInput reads a lone input for its proportions): the next
  //! get() that reads `source` with the same options takes it instead of reading the file
  //! again, and the cache lets it go once its mesh is made.
  void keepRead(const std::filesystem::path& source, const terrain::HeightfieldOptions& options,
                terrain::Heightfield h);
  void keepRead(const std::filesystem::path& source, mesh::PolygonSoup soup);

 private:
  //! Lets go of what was read ahead of `source` under other options (a --set that changed
  //! how the file is read): its mesh is made.
  void dropReads(const std::filesystem::path& source);

  std::map<std::string, std::shared_ptr<terrain::Heightfield>> read_heightfields_;
  std::map<std::string, mesh::PolygonSoup> read_soups_;
  std::map<std::string, std::shared_ptr<const ObjectAsset>> meshes_;
  std::map<std::string, std::shared_ptr<const image::Image>> images_;
  std::map<std::string, std::shared_ptr<const ElementSet>> elements_;
};

//! Prepares a loaded mesh for object `o`: recentres it when asked, makes planar UVs or checks
//! the mesh's own when the object is wrinkled (Error naming `where` otherwise), computes
//! normals and, when the object draws lines, curvature and the feature size. A mesh (not a
//! DEM) whose normals are not the file's own (`file_normals`) gets them split at its
//! creases (objects.N.crease_angle); curvature is measured before, on the welded mesh.
ObjectAsset prepareAsset(mesh::Mesh m, const Object& o, const std::string& where = "object", bool file_normals = false);

//! The axis (0 x, 1 y, 2 z) a flat piece of `extent` lies on: the one under half of both
//! others, as a piece of land is; -1 when there is none. `up: auto`'s rule for meshes.
int flatAxis(const glm::dvec3& extent);

//! Planar UVs: x and y over the larger horizontal extent of the mesh, in [0, 1].
void planarUvs(mesh::Mesh& m);

//! Eq. 5's grey value, dot(rgb, (0.3, 0.59, 0.11)), of every pixel (grey images as is).
image::Image wrinkleLuma(const image::Image& img);

}  // namespace shanshui::scene
