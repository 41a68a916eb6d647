#include "shanshui/scene/scene.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/scene/scene_assets.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::scene {

using nlohmann::json;

glm::dmat4 Transform::matrix() const {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotate_deg.z), {0, 0, 1});
  m = glm::rotate(m, glm::radians(rotate_deg.y), {0, 1, 0});
  m = glm::rotate(m, glm::radians(rotate_deg.x), {1, 0, 0});
  return glm::scale(m, scale);
}

bool Scene::usesMarks() const {
  return std::any_of(objects.begin(), objects.end(),
                     [](const Object& o) { return o.marks.enabled() || o.marks.washes(); });
}

bool Scene::usesWash() const {
  return std::any_of(objects.begin(), objects.end(), [](const Object& o) { return o.marks.washes(); });
}

bool Scene::isComposition() const {
  return std::count_if(objects.begin(), objects.end(),
                       [](const Object& o) { return !o.dem.empty() && !o.grounded(); }) > 1;
}

std::filesystem::path Scene::resolve(const std::string& relative) const {
  const std::filesystem::path p(relative);
  return p.is_absolute() ? p : base_dir / p;
}

namespace {
template <typename Pred>
bool anyObject(const std::vector<Object>& objects, Pred pred) {
  return std::any_of(objects.begin(), objects.end(), pred);
}
}  // namespace

int Output::pixelWidth() const {
  if (format == Format::Free) return width;
  return std::max(1, static_cast<int>(std::lround(kScrollAspect * height)));
}

namespace {
// Rice paper drawn by the tiles method, the one that draws marks.
bool tiledRicePaper(const Canvas& c) {
  return c.type != CanvasType::None && c.type != CanvasType::Static && c.method == CanvasMethod::Tiles &&
         c.pattern() == CanvasPattern::RicePaper;
}
}  // namespace

bool Canvas::hasFibresOrSpots() const {
  return tiledRicePaper(*this) && (fibres > 0 || spots > 0);
}

bool Canvas::hasMottle() const {
  return tiledRicePaper(*this) && mottle > 0;
}

bool Scene::usesWrinkles() const {
  return anyObject(objects, [](const Object& o) { return o.wrinkled(); });
}

bool Scene::usesLines() const {
  return anyObject(objects, [](const Object& o) { return o.lines.enabled; });
}

bool Scene::usesStrokes() const {
  return anyObject(objects, [](const Object& o) { return o.lines.strokes(); });
}

bool Scene::usesPigment() const {
  return anyObject(objects, [](const Object& o) { return o.pigment.enabled(); });
}

bool Scene::usesBrushStrokes() const {
  return anyObject(objects, [](const Object& o) { return o.strokes.enabled(); });
}

bool Scene::usesSuggestiveContours() const {
  return anyObject(objects, [](const Object& o) { return o.lines.suggestiveContours(); });
}

glm::dvec3 Object::pathOffset(double t) const {
  if (path.empty()) return glm::dvec3(0.0);
  if (t <= path.front().time) return path.front().offset;
  if (t >= path.back().time) return path.back().offset;
  const auto next =
      std::upper_bound(path.begin(), path.end(), t, [](double time, const PathKey& k) { return time < k.time; });
  const PathKey &a = *(next - 1), &b = *next;
  return glm::mix(a.offset, b.offset, (t - a.time) / (b.time - a.time));
}

bool Scene::hasAnimation() const {
  return anyObject(objects, [](const Object& o) { return o.animated(); });
}

bool Scene::dissolvesBorders() const {
  return anyObject(objects, [](const Object& o) { return o.dissolvesBorder(); });
}

bool Scene::usesShading() const {
  return anyObject(objects, [](const Object& o) { return o.shading.enabled; });
}

bool Scene::usesElements() const {
  return anyObject(objects, [](const Object& o) { return o.hasElements(); });
}

namespace {

std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : path) {
    if (c == '.') {
      parts.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

// Deepest nesting of arrays and objects in JSON text (strings skipped), so a value nested
// 100 000 deep is refused before the parser recurses into it.
int jsonDepth(std::string_view text) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

constexpr int kMaxJsonDepth = 64;
constexpr std::uintmax_t kMaxSceneBytes = 64u << 20;

// Parses JSON text, naming `what` (the file, or --set KEY) in every error.
json parseJsonText(std::string_view text, const std::string& what) {
  if (const int depth = jsonDepth(text); depth > kMaxJsonDepth) {
    throw makeError(what, ": JSON nested ", depth, " levels deep; at most ", kMaxJsonDepth, " are allowed");
  }
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    std::string msg = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 2: ..." -> the part after "] ".
    if (const auto cut = msg.find("] "); cut != std::string::npos) msg = msg.substr(cut + 2);
    throw makeError(what, ": not valid JSON: ", msg);
  }
}

}  // namespace

void applyOverride(json& j, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw makeError("--set: '", assignment, "' is not KEY=VALUE (e.g. objects.0.lines.curve_factor=2)");
  }
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  if (jsonDepth(text) > kMaxJsonDepth) {
    throw makeError("--set ", key, ": value nested more than ", kMaxJsonDepth, " levels deep");
  }
  json value = json::parse(text, nullptr, false);
  if (value.is_discarded()) value = text;  // a plain string, e.g. canvas.type=none
  json* node = &j;
  std::string walked;
  for (const std::string& part : splitPath(key)) {
    if (part.empty()) throw makeError("--set: '", key, "' has an empty path component");
    walked += (walked.empty() ? "" : ".") + part;
    if (node->is_array()) {
      const bool digits = part.find_first_not_of("0123456789") == std::string::npos;
      std::size_t index = 0;
      const bool fits = digits && part.size() <= 9;  // a list never has a billion objects
      if (fits) index = static_cast<std::size_t>(std::stoul(part));
      if (!fits || index >= node->size()) {
        throw makeError("--set ", key, ": ", walked, ": no such element (the list has ", node->size(), ")");
      }
      node = &(*node)[index];
    } else {
      if (node->is_null()) *node = json::object();
      if (!node->is_object()) throw makeError("--set ", key, ": ", walked, ": the parent is not an object");
      node = &(*node)[part];
    }
  }
  *node = value;
}

Scene loadScene(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  json j = parseJsonText(readInputFile(path, "a scene (JSON)", kMaxSceneBytes), path.string());
  if (!j.is_object()) {
    throw makeError(path.string(), ": a scene is a JSON object ({...}), found ", j.type_name());
  }
  for (const std::string& o : overrides) applyOverride(j, o);
  return parseScene(j, path.filename().string(), path.parent_path().empty() ? "." : path.parent_path());
}

namespace {

// Land flatter than this (relief over the larger horizontal side) is raised to it when a lone
// DEM is painted: about St. Helens' and the sample hill's proportions lie above (0.13, 0.22),
// a 1-degree SRTM tile of the Alps (~0.03) or a coast 300 km wide (~0.01) below, and those
// drawn true to scale are a plain with a rough skin.
constexpr double kLeastReliefRatio = 0.1;
constexpr double kMostLoneZScale = 20.0;
// Share of the samples at or below 0 m and open to the grid's edge (seaSamples) that makes
// the lone DEM's sea, and how far above 0 m its surface lies (of the relief), so that a sea
// stored as 0 m (SRTM, ASTER) is under it.
constexpr double kLeastSeaShare = 0.01;
constexpr double kSeaLevelAbove = 0.002;
// Land at most this wide (metres, its larger side) grows trees and moss dots at their real
// size: on St. Helens (14 km) they are groves of small marks along its ridges and gullies;
// on a coast 300 km wide they would be specks, and millions of them.
constexpr double kMostWoodedSide = 20000.0;
// A lone DEM with fewer samples than this along its larger side is made finer
// (terrain::upsample) until it has them: a grid of 120 cells across a 1024-pixel picture
// draws each cell 6-8 pixels wide, and its coasts and islands as polygons.
constexpr int kLeastLoneSamples = 400;

// printf into a string (the notes' numbers are rounded as a reader wants them).
template <typename... Args>
std::string formatted(const char* format, Args... args) {
  char text[256];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

// What lone land (a DEM, or a mesh that is a piece of land) gets from its own proportions:
// vertical exaggeration, trees and dots, and (a DEM's heights being elevations) a sea.
struct LandLook {
  bool land = false;  //!< painted as land: the deep preset, mist, a dissolving border, wet strokes
  double z_scale = 1.0;
  std::optional<double> water_level;  //!< fraction of the relief from the lowest sample
  bool wooded = false;                //!< trees and moss dots
  int upsample = 1;                   //!< a DEM's objects.0.upsample
  int subdivide = 0;                  //!< a land mesh's objects.0.subdivide
  std::string land_note, relief_note, sea_note, dry_note, wooded_note, upsample_note, subdivide_note;
};

// Raised when flatter than kLeastReliefRatio; trees and dots when at most kMostWoodedSide
// across. `key` is what raises it (a DEM's z_scale, a mesh's transform). False, and nothing
// decided, when the relief or the side is not a positive finite length.
bool proportions(LandLook& look, double side, double relief, const char* key) {
  if (!(relief > 0.0) || !std::isfinite(relief) || !(side > 0.0) || !std::isfinite(side)) return false;
  const double ratio = relief / side;
  if (side <= kMostWoodedSide) {
    look.wooded = true;
    look.wooded_note = formatted(
        "%.3g km across: trees and moss dots grown (objects.0.trees.enabled, "
        "objects.0.dots.enabled)",
        side / 1000.0);
  }
  if (ratio < kLeastReliefRatio) {
    look.z_scale = std::min(kLeastReliefRatio / ratio, kMostLoneZScale);
    look.relief_note = formatted("relief %.0f m over %.3g km (1:%.0f) raised %.3g times (%s)", relief, side / 1000.0,
                                 1.0 / ratio, look.z_scale, key);
  }
  return true;
}

// The samples at or below 0 m that are sea, open to the grid's edge through samples at or
// below 0 m (or without data: a coast whose sea is stored as no data still reaches it), and
// those in basins closed from every edge (Death Valley, the Jordan valley): land below sea
// level, which a water level at 0 m would flood. A flood fill over 4-neighbours.
std::pair<std::size_t, std::size_t> seaSamples(const terrain::Heightfield& h) {
  const int w = h.columns, n = h.rows;
  auto low = [&](int c, int r) { return !(h.at(c, r) > 0.0); };  // NaN too
  std::vector<char> open(static_cast<std::size_t>(w) * static_cast<std::size_t>(n), 0);
  std::vector<std::pair<int, int>> todo;
  auto reach = [&](int c, int r) {
    if (c < 0 || r < 0 || c >= w || r >= n || !low(c, r)) return;
    char& o = open[static_cast<std::size_t>(r) * w + c];
    if (!o) {
      o = 1;
      todo.emplace_back(c, r);
    }
  };
  for (int c = 0; c < w; ++c) reach(c, 0), reach(c, n - 1);
  for (int r = 0; r < n; ++r) reach(0, r), reach(w - 1, r);
  while (!todo.empty()) {
    const auto [c, r] = todo.back();
    todo.pop_back();
    reach(c - 1, r), reach(c + 1, r), reach(c, r - 1), reach(c, r + 1);
  }
  std::size_t sea = 0, inland = 0;
  for (std::size_t i = 0; i < h.elevation.size(); ++i) {
    if (!(h.elevation[i] <= 0.0)) continue;  // land, or no data
    if (open[i]) {
      ++sea;
    } else {
      ++inland;
    }
  }
  return {sea, inland};
}

LandLook demLook(const terrain::Heightfield& h) {
  LandLook look;
  look.land = true;
  const auto [lo, hi] = h.elevationRange();
  const double side = std::max(h.columns * h.cell_x, h.rows * h.cell_y), relief = hi - lo;
  look.upsample = terrain::upsampleFactor(h, kLeastLoneSamples, Object{}.max_vertices);
  if (look.upsample > 1) {
    look.upsample_note = formatted("%d x %d samples: made %d times finer by bicubic interpolation (objects.0.upsample)",
                                   h.columns, h.rows, look.upsample);
  }
  if (!proportions(look, side, relief, "objects.0.z_scale")) return look;  // the sea divides by the relief
  const auto [sea, inland] = seaSamples(h);
  const double valid = static_cast<double>(std::max<std::size_t>(h.validCount(), 1));
  const double share = static_cast<double>(sea) / valid, dry = static_cast<double>(inland) / valid;
  if (hi > 0.0 && share >= kLeastSeaShare) {
    look.water_level = std::clamp(-lo / relief + kSeaLevelAbove, 0.0, 1.0);
    look.sea_note =
        formatted("%.0f %% of it at or below 0 m is sea (water.level %.3f)", 100.0 * share, *look.water_level);
  } else if (hi > 0.0 && dry >= kLeastSeaShare) {
    look.dry_note = formatted(
        "%.0f %% of it lies at or below 0 m in basins closed from its edges, land below sea level, not "
        "sea: left dry (water.enabled=true floods it)",
        100.0 * dry);
  }
  return look;
}

// Read as the asset cache will read it (the same options), and handed to `cache` so it is not
// read again; a file that does not load is left to the cache to report, with the plain look.
LandLook loneDemLook(const std::filesystem::path& path, AssetCache* cache) {
  terrain::HeightfieldOptions options;
  options.image_relief_ratio = kImageReliefRatio;
  options.max_samples = Object{}.max_vertices;
  terrain::Heightfield h;
  try {
    h = terrain::loadHeightfield(path, options);
  } catch (const std::exception&) {
    LandLook look;
    look.land = true;
    return look;
  }
  LandLook look = demLook(h);
  if (cache) cache->keepRead(path, options, std::move(h));
  return look;
}

// A lone mesh that is a piece of land (a terrain from a GIS or a photogrammetry tool,
// shanshui-terrain's own output) is painted as a DEM is: it is flat along one axis (the axis
// the asset cache takes as up, scene_assets.cpp's upAxis: under half of both others) and
// faces up over nearly all its area, as a heightfield does. A building, a boulder or a boat
// is closed, so about half its area faces down or sideways. Units are taken as metres.
constexpr double kLeastUpShare = 0.85;
// A lone land mesh with fewer vertices than this is Loop-subdivided (at most 3 times) until
// it has them: a low-poly land's creases along its triangles' edges are drawn as ladders of
// short lines, its facets as flat tones.
constexpr std::size_t kLeastLandVertices = 4000;

LandLook meshLook(const mesh::PolygonSoup& soup, const std::string& asked_up) {
  LandLook look;
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::dvec3& p : soup.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 e = hi - lo;
  // The up axis given (objects.0.up), or the one `auto` takes; without either, not land.
  int up = asked_up == "x" ? 0 : asked_up == "y" ? 1 : asked_up == "z" ? 2 : flatAxis(e);
  if (up < 0) return look;
  double total = 0.0, facing_up = 0.0;
  for (const std::vector<std::uint32_t>& f : soup.faces) {
    for (std::size_t k = 2; k < f.size(); ++k) {  // a fan: a polygon's area and mean normal
      if (f[0] >= soup.positions.size() || f[k - 1] >= soup.positions.size() || f[k] >= soup.positions.size()) continue;
      const glm::dvec3 a = soup.positions[f[0]];
      const glm::dvec3 n = glm::cross(soup.positions[f[k - 1]] - a, soup.positions[f[k]] - a);
      const double area = glm::length(n);
      if (!std::isfinite(area) || area <= 0.0) continue;
      total += area;
      if (n[up] > 0.3 * area) facing_up += area;
    }
  }
  if (!(total > 0.0) || facing_up < kLeastUpShare * total) return look;
  look.land = true;
  look.land_note = formatted(
      "a piece of land (%.0f %% of its surface faces up): painted as a DEM is "
      "(camera.preset deep, mist, objects.0.border.mode dissolve, wet strokes)",
      100.0 * facing_up / total);
  proportions(look, std::max(e[(up + 1) % 3], e[(up + 2) % 3]), e[up], "objects.0.transform.scale");
  for (std::size_t v = soup.positions.size(); v < kLeastLandVertices && look.subdivide < 3 && v > 0; v *= 4)
    ++look.subdivide;
  if (look.subdivide > 0) {
    const char* times[] = {"", "once", "twice", "3 times"};
    look.subdivide_note = formatted("%zu vertices: Loop-subdivided %s (objects.0.subdivide)", soup.positions.size(),
                                    times[look.subdivide]);
  }
  return look;
}

// As loneDemLook: read once, and handed to `cache`.
LandLook loneMeshLook(const std::filesystem::path& path, const std::string& asked_up, AssetCache* cache) {
  mesh::PolygonSoup soup;
  try {
    soup = mesh::readPolygonSoup(path);
  } catch (const std::exception&) {
    return {};  // the asset cache reports it
  }
  LandLook look = meshLook(soup, asked_up);
  if (cache) cache->keepRead(path, std::move(soup));
  return look;
}

}  // namespace

// What a lone input is, by its extension: meshes through shanshui's own readers or Assimp,
// heightfields through shanshui's own readers or GDAL (mesh_io.h, heightfield.h). Each list
// holds the formats people bring; a scene file names any other the libraries read.
constexpr std::array kLoneMeshExtensions{".obj", ".ply", ".off", ".gltf", ".glb", ".fbx",  ".dae",
                                         ".3ds", ".stl", ".3mf", ".x3d",  ".lwo", ".blend"};
constexpr std::array kLoneDemExtensions{".dem", ".asc", ".png", ".tif", ".tiff", ".hgt", ".img", ".vrt",
                                        ".bil", ".bt",  ".dt0", ".dt1", ".dt2",  ".jp2", ".grd", ".flt"};

Scene loadSceneInput(const std::filesystem::path& path, const std::vector<std::string>& overrides,
                     std::vector<std::string>* notes, AssetCache* cache) {
  std::string ext = path.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".json") return loadScene(path, overrides);
  auto listed = [&](const auto& list) { return std::find(list.begin(), list.end(), ext) != list.end(); };
  const bool mesh = listed(kLoneMeshExtensions), dem = listed(kLoneDemExtensions);
  if (!mesh && !dem) {
    auto names = [](const auto& list) {
      std::string text;
      for (const char* e : list) text += std::string(text.empty() ? "" : " ") + e;
      return text;
    };
    throw makeError(path.string(), ": expected a scene (.json), a mesh (", names(kLoneMeshExtensions),
                    ") or a heightfield (", names(kLoneDemExtensions), ")");
  }
  // The sample scene's style: strokes, light tones that leave lit slopes white, strong aerial
  // perspective, rice paper; land (a DEM, or a mesh that is a piece of land) is seen from
  // above into its ranges with mist in its valleys, any other mesh is an object filling the
  // frame. Trees and dots only on land a few kilometres across (proportions): on a coast
  // 300 km wide the default density would ask for millions.
  json object = {{mesh ? "mesh" : "dem", path.string()},
                 {"name", path.stem().string()},
                 {"lines", {{"width", 4.67}}},  // 3.5 pixels at the default 768 high
                 {"shading", {{"tones", {0.5, 0.66, 0.8, 0.92, 1.0}}}}};
  json j = {{"objects", json::array({object})}, {"canvas", {{"type", "rice_paper"}}}, {"output", {{"fade", 0.6}}}};
  // Land flatter than a painter's is raised, a coast or a topo-bathymetric grid gets its sea
  // as water, land a few kilometres across its trees (kLeastReliefRatio, kLeastSeaShare,
  // kMostWoodedSide).
  std::string asked_up = "auto";  // a mesh's up axis as --set gives it, before the look is chosen
  if (mesh) {
    json probe = j;
    for (const std::string& o : overrides) applyOverride(probe, o);
    const json& up = probe["objects"][0]["up"];
    if (up.is_string()) asked_up = up.get<std::string>();
  }
  const LandLook look = dem ? loneDemLook(path, cache) : loneMeshLook(path, asked_up, cache);
  if (look.land) {
    j["camera"] = {{"preset", "deep"}};
    j["mist"] = {{"density", 0.75}, {"height", 0.12}, {"softness", 0.35}};
    // Land gets broad wet strokes on its shadowed flanks, as a painter builds a slope's mass:
    // in three cells of five (so no regular rows on a smooth hill), halfway between the fall
    // line, which they follow round a hill's form, and straight down the sheet, which keeps
    // them whole on a DEM's rough ground. A lone object may be a building or a boat: none.
    j["objects"][0]["marks"] = {
        {"wash", 0.6}, {"wash_size", 100}, {"wash_width", 1.8}, {"wash_ink", 0.7}, {"wash_follow", 0.5}};
    if (mesh) j["objects"][0]["border"] = {{"mode", "dissolve"}};  // a DEM's by default
  } else {
    j["camera"] = {{"framing", "fill"}};
  }
  if (look.z_scale != 1.0) {
    if (dem) {
      j["objects"][0]["z_scale"] = look.z_scale;
    } else {
      j["objects"][0]["transform"] = {{"scale", {1.0, 1.0, look.z_scale}}};  // applied with z up
    }
  }
  if (look.upsample > 1) j["objects"][0]["upsample"] = look.upsample;
  if (look.subdivide > 0) j["objects"][0]["subdivide"] = look.subdivide;
  if (look.water_level) j["water"] = {{"enabled", true}, {"level", *look.water_level}};
  if (look.wooded) {
    j["objects"][0]["trees"] = {{"enabled", true}};
    j["objects"][0]["dots"] = {{"enabled", true}};
  }
  for (const std::string& o : overrides) applyOverride(j, o);
  Scene s = parseScene(j, path.filename().string(), ".");
  // Said unless an override changed it.
  if (notes) {
    const Object& o = s.objects[0];
    if (!look.land_note.empty() && s.camera.preset == CameraPreset::Deep && o.dissolvesBorder())
      notes->push_back(look.land_note);
    const double raised = dem ? o.z_scale : o.transform.scale.z;
    if (!look.relief_note.empty() && raised == look.z_scale) notes->push_back(look.relief_note);
    if (look.water_level && s.water.enabled && s.water.level == *look.water_level) notes->push_back(look.sea_note);
    if (!look.dry_note.empty() && !s.water.enabled) notes->push_back(look.dry_note);
    if (look.wooded && o.trees.enabled && o.dots.enabled) notes->push_back(look.wooded_note);
    if (look.upsample > 1 && o.upsample == look.upsample) notes->push_back(look.upsample_note);
    if (look.subdivide > 0 && o.subdivide == look.subdivide) notes->push_back(look.subdivide_note);
  }
  return s;
}

void saveScene(const Scene& s, const std::filesystem::path& path) {
  // File paths are rewritten relative to where the scene is saved, so it loads from there.
  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(path).parent_path();
  Scene saved = s;
  auto rebase = [&](std::string& p) {
    if (!p.empty()) p = fs::proximate(fs::absolute(s.resolve(p)).lexically_normal(), dir).generic_string();
  };
  for (Object& o : saved.objects) {
    rebase(o.mesh);
    rebase(o.dem);
    rebase(o.wrinkle.texture);
  }
  rebase(saved.substrate.texture);
  // A file name that is not UTF-8 is written with U+FFFD in its place rather than failing.
  const std::string text = toJson(saved).dump(2, ' ', false, json::error_handler_t::replace) + "\n";
  writeFileAtomically(path, text);
}

}  // namespace shanshui::scene
