#include "shanshui/scene/scene_assets.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "shanshui/core/error.h"
#include "shanshui/image/image_io.h"
#include "shanshui/mesh/curvature.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/terrain/heightfield.h"
#include "shanshui/terrain/terrain_mesh.h"

namespace shanshui::scene {

namespace {
// The most triangles objects.N.subdivide makes: a step that would make more is not taken.
constexpr std::size_t kMostSubdividedTriangles = std::size_t{1} << 21;
}  // namespace

void planarUvs(mesh::Mesh& m) {
  const mesh::Bounds b = mesh::bounds(m);
  const double extent = std::max({b.size().x, b.size().y, 1e-300});
  m.uvs.resize(m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    m.uvs[i] = glm::vec2((m.positions[i].x - b.min.x) / extent, (m.positions[i].y - b.min.y) / extent);
  }
}

image::Image wrinkleLuma(const image::Image& img) {
  image::Image out(img.width, img.height, 1);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  for (std::size_t i = 0; i < n; ++i) {
    const float* p = &img.pixels[i * img.channels];
    out.pixels[i] = img.channels >= 3 ? 0.3f * p[0] + 0.59f * p[1] + 0.11f * p[2] : p[0];
  }
  return out;
}

int flatAxis(const glm::dvec3& extent) {
  for (int axis = 0; axis < 3; ++axis)
    if (extent[axis] < 0.5 * std::min(extent[(axis + 1) % 3], extent[(axis + 2) % 3])) return axis;
  return -1;
}

namespace {

UpAxis upAxis(const Object& o, const mesh::Mesh& m) {
  if (o.up != UpAxis::Auto) return o.up;
  if (!o.dem.empty()) return UpAxis::Z;
  // A flat piece of land (or anything much thinner along one axis) lies on its thin axis,
  // whichever tool wrote it; any other mesh follows the OBJ/PLY convention of Y up.
  const int axis = flatAxis(mesh::bounds(m).size());
  return axis == 0 ? UpAxis::X : axis == 2 ? UpAxis::Z : UpAxis::Y;
}

void makeZUp(mesh::Mesh& m, UpAxis up) {
  // Rotations (determinant +1), so faces keep their winding: Y-up (x, y, z) -> (x, -z, y),
  // X-up (x, y, z) -> (y, z, x).
  auto turn = [up](auto v) -> decltype(v) {
    if (up == UpAxis::Y) return {v.x, -v.z, v.y};
    if (up == UpAxis::X) return {v.y, v.z, v.x};
    return v;
  };
  if (up == UpAxis::Z || up == UpAxis::Auto) return;
  for (glm::dvec3& p : m.positions) p = turn(p);
  for (glm::vec3& n : m.normals) n = turn(n);
}

}  // namespace

ObjectAsset prepareAsset(mesh::Mesh m, const Object& o, const std::string& where, bool file_normals) {
  ObjectAsset asset;
  const bool wrinkled = !o.wrinkle.texture.empty() && o.shading.enabled;
  makeZUp(m, upAxis(o, m));
  if (o.recentre) mesh::recentre(m);
  if (wrinkled && o.wrinkle.uv == UvSource::Planar) planarUvs(m);
  if (wrinkled && m.uvs.size() != m.positions.size()) {
    throw makeError(where, ".wrinkle.uv: ", o.mesh.empty() ? o.dem : o.mesh,
                    " has no UVs; parameterize it with shanshui-param or use \"uv\": \"planar\"");
  }
  if (!wrinkled) m.uvs.clear();
  if (m.normals.size() != m.positions.size()) m.normals = mesh::vertexNormals(m);
  if (o.lines.enabled) {  // the feature size serves both curvature sources
    mesh::VertexCurvature c =
        o.lines.curvature == CurvatureSource::Quadric ? mesh::estimateCurvatureByFit(m) : mesh::estimateCurvature(m);
    mesh::smoothOverOneRing(m, c.magnitude, o.lines.smoothing);
    asset.feature_size = mesh::curvatureFeatureSize(m, c);
    if (perVertex(o.lines.curvature)) {
      asset.curvature.resize(c.magnitude.size());
      for (std::size_t i = 0; i < c.magnitude.size(); ++i) {
        asset.curvature[i] = static_cast<float>(c.magnitude[i] * asset.feature_size);
      }
    }
  }
  if (o.dem.empty() && !file_normals && o.crease_angle < 180.0) {
    const std::vector<std::uint32_t> origin = mesh::splitAtCreases(m, o.crease_angle);
    if (!asset.curvature.empty() && origin.size() != asset.curvature.size()) {
      std::vector<float> split(origin.size());
      for (std::size_t i = 0; i < origin.size(); ++i) split[i] = asset.curvature[origin[i]];
      asset.curvature = std::move(split);
    }
  }
  asset.bounds = mesh::bounds(m);
  asset.mesh = std::move(m);
  return asset;
}

namespace {

std::string where(std::size_t index, const char* key) {
  return "objects." + std::to_string(index) + "." + key;
}

// A file as the read-ahead maps know it: the same file however the path to it was written.
std::string fileKey(const std::filesystem::path& source) {
  return std::filesystem::absolute(source).lexically_normal().string();
}

std::string heightfieldKey(const std::filesystem::path& source, const terrain::HeightfieldOptions& o) {
  std::ostringstream k;
  k.precision(17);
  k << fileKey(source) << "|" << o.cell_size << " " << o.image_relief_ratio << " " << o.max_geographic_scale_error
    << " " << o.max_samples << " " << o.fill_nodata << " " << o.crop[0] << " " << o.crop[1] << " " << o.crop[2] << " "
    << o.crop[3];
  return k.str();
}

// What was read ahead under `key`, taken out of `kept`; otherwise read(): each file read once.
template <typename T, typename Read>
T takeOrRead(std::map<std::string, T>& kept, const std::string& key, Read read) {
  const auto it = kept.find(key);
  if (it == kept.end()) return read();
  T value = std::move(it->second);
  kept.erase(it);
  return value;
}

}  // namespace

void AssetCache::keepRead(const std::filesystem::path& source, const terrain::HeightfieldOptions& options,
                          terrain::Heightfield h) {
  read_heightfields_[heightfieldKey(source, options)] = std::make_shared<terrain::Heightfield>(std::move(h));
}

void AssetCache::keepRead(const std::filesystem::path& source, mesh::PolygonSoup soup) {
  read_soups_[fileKey(source)] = std::move(soup);
}

void AssetCache::dropReads(const std::filesystem::path& source) {
  const std::string file = fileKey(source);
  read_soups_.erase(file);
  std::erase_if(read_heightfields_, [&](const auto& kept) { return kept.first.starts_with(file + "|"); });
}

LoadedObject AssetCache::get(const Scene& scene, std::size_t index) {
  const Object& o = scene.objects.at(index);
  const bool wrinkled = !o.wrinkle.texture.empty() && o.shading.enabled;
  const bool object_curvature = o.lines.enabled;  // the feature size serves every source
  const int curvature = o.lines.enabled ? static_cast<int>(o.lines.curvature) : -1;
  const std::filesystem::path source = scene.resolve(o.mesh.empty() ? o.dem : o.mesh);
  const std::string key =
      source.string() + "|" + std::to_string(o.z_scale) + "|" + std::to_string(o.max_vertices) + "|" +
      std::to_string(o.cell_size) + "|" + std::to_string(o.fill_nodata) + std::to_string(o.smooth_steps) + "|" +
      std::to_string(o.upsample) + "|" + std::to_string(o.crease_angle) + " " + std::to_string(o.subdivide) + "|" +
      std::to_string(o.crop[0]) + " " + std::to_string(o.crop[1]) + " " + std::to_string(o.crop[2]) + " " +
      std::to_string(o.crop[3]) + "|" + std::to_string(static_cast<int>(o.up)) + "|" + std::to_string(o.recentre) +
      "|" + std::to_string(object_curvature) + std::to_string(curvature) + "|" + std::to_string(o.lines.smoothing) +
      "|" + (wrinkled ? (o.wrinkle.uv == UvSource::Mesh ? "uv-mesh" : "uv-planar") : "no-uv");
  std::shared_ptr<const ObjectAsset>& slot = meshes_[key];
  std::shared_ptr<const image::Image> wrinkle;
  if (wrinkled) {
    const std::filesystem::path tex = scene.resolve(o.wrinkle.texture);
    auto& img = images_[tex.string()];
    if (!img) {
      try {
        img = std::make_shared<const image::Image>(wrinkleLuma(image::loadImage(tex)));
      } catch (const Error& e) {
        images_.erase(tex.string());
        throw makeError(where(index, "wrinkle.texture"), ": ", e.what());
      }
    }
    wrinkle = img;
  }
  if (!slot) {
    const auto start = std::chrono::steady_clock::now();
    auto asset = std::make_shared<ObjectAsset>();
    bool file_normals = false;
    try {
      if (!o.dem.empty()) {
        terrain::TerrainMeshOptions topt;
        topt.z_scale = o.z_scale;
        topt.max_vertices = o.max_vertices;
        terrain::HeightfieldOptions hopt;
        hopt.cell_size = o.cell_size;
        hopt.image_relief_ratio = kImageReliefRatio;
        hopt.max_samples = o.max_vertices;
        hopt.fill_nodata = o.fill_nodata;
        hopt.crop = o.crop;
        // Taken out of the read-ahead map or read now: this call's own, so smoothed in place.
        const std::shared_ptr<terrain::Heightfield> field =
            takeOrRead(read_heightfields_, heightfieldKey(source, hopt),
                       [&] { return std::make_shared<terrain::Heightfield>(terrain::loadHeightfield(source, hopt)); });
        // Heights stored in whole metres (or tenths, or grey levels) are smoothed within
        // their steps: otherwise the treads' edges on gentle ground are drawn as cracks.
        if (o.smooth_steps) terrain::dequantize(*field);
        // Finer by the factor asked, or by the most that stays within the mesh's vertices.
        int factor = o.upsample;
        while (factor > 1 && terrain::upsampledSamples(*field, factor) > static_cast<double>(o.max_vertices)) --factor;
        terrain::upsample(*field, factor, where(index, "upsample"));
        asset->mesh = terrain::heightfieldToMesh(*field, topt, nullptr, source.string());
      } else {
        // Every component is drawn (a teapot's lid and spout); only parameterisation
        // needs a single disc.
        mesh::RepairOptions ropt;
        ropt.components = mesh::ComponentPolicy::KeepAll;
        const mesh::PolygonSoup soup =
            takeOrRead(read_soups_, fileKey(source), [&] { return mesh::readPolygonSoup(source); });
        asset->mesh = mesh::repairMesh(soup, ropt, nullptr, source.string());
        // The file's normals survive repair only where it kept the file's vertices.
        file_normals = !soup.normals.empty() && asset->mesh.normals == soup.normals;
        // The steps asked for, or the most that stay within kMostSubdividedTriangles.
        int steps = o.subdivide;
        while (steps > 0 && (asset->mesh.triangles.size() << (2 * steps)) > kMostSubdividedTriangles) --steps;
        if (steps > 0) {
          asset->mesh =
              mesh::subdivideLoop(asset->mesh, steps, source.string() + " (" + where(index, "subdivide") + ")");
          file_normals = false;
        }
      }
    } catch (const Error& e) {
      meshes_.erase(key);
      throw makeError(where(index, o.dem.empty() ? "mesh" : "dem"), ": ", e.what());
    }
    dropReads(source);
    try {
      *asset = prepareAsset(std::move(asset->mesh), o, "objects." + std::to_string(index), file_normals);
    } catch (const Error&) {
      meshes_.erase(key);
      throw;
    }
    asset->load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    slot = std::move(asset);
  }
  std::shared_ptr<const ElementSet> grown;
  if (o.hasElements()) {
    // Placed once per mesh and placement options; the drawing keys (ink, dot size) are not
    // part of it.
    const elements::TreeOptions& t = o.trees;
    const elements::DotOptions& d = o.dots;
    std::ostringstream k;
    k.precision(17);
    k << key << "|" << scene.seed << "|" << t.enabled << " " << t.density << " " << t.size << " " << t.size_spread
      << " " << t.max_slope_deg << " " << t.band[0] << " " << t.band[1] << " " << t.open << " " << t.grove << " "
      << t.grove_radius << " " << t.kinds[0] << " " << t.kinds[1] << " " << t.kinds[2] << " " << t.kinds[3] << " "
      << t.seed << " " << t.massed_beyond << "|" << d.enabled << " " << d.density << " " << d.cluster << " " << d.spread
      << " " << d.at_trees << " " << d.seed << " " << d.massed_beyond;
    std::shared_ptr<const ElementSet>& placed = elements_[k.str()];
    if (!placed) {
      const auto start = std::chrono::steady_clock::now();
      auto set = std::make_shared<ElementSet>();
      try {
        set->instances = elements::placeElements(slot->mesh, t, d, scene.seed, "objects." + std::to_string(index));
      } catch (const Error&) {
        elements_.erase(k.str());
        throw;
      }
      set->place_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      placed = std::move(set);
    }
    grown = placed;
  }
  return {slot, wrinkle, grown};
}

std::vector<LoadedObject> AssetCache::getAll(const Scene& scene) {
  std::vector<LoadedObject> out;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) out.push_back(get(scene, i));
  return out;
}

}  // namespace shanshui::scene
