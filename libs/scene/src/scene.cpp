#include "shanshui/scene/scene.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"

namespace shanshui::scene {

using nlohmann::json;

glm::dmat4 Transform::matrix() const {
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), translate);
  m = glm::rotate(m, glm::radians(rotate_deg.z), {0, 0, 1});
  m = glm::rotate(m, glm::radians(rotate_deg.y), {0, 1, 0});
  m = glm::rotate(m, glm::radians(rotate_deg.x), {1, 0, 0});
  return glm::scale(m, scale);
}

std::filesystem::path Scene::resolve(const std::string& relative) const {
  const std::filesystem::path p(relative);
  return p.is_absolute() ? p : base_dir / p;
}

bool Scene::usesWrinkles() const {
  for (const Object& o : objects) {
    if (!o.wrinkle.texture.empty() && o.shading.enabled) return true;
  }
  return false;
}

bool Scene::usesLines() const {
  for (const Object& o : objects) {
    if (o.lines.enabled) return true;
  }
  return false;
}

bool Scene::hasAnimation() const {
  for (const Object& o : objects) {
    if (o.animated()) return true;
  }
  return false;
}

bool Scene::usesShading() const {
  for (const Object& o : objects) {
    if (o.shading.enabled) return true;
  }
  return false;
}

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Reads one JSON object, remembering which keys were used so the rest can be reported as
// unknown, and (when building the schema) recording every key with its kind and range.
class Reader {
 public:
  Reader(const json* j, std::string path, const std::string& origin, std::vector<SchemaEntry>* schema)
      : j_(j), path_(std::move(path)), origin_(origin), schema_(schema) {
    if (j_ && !j_->is_object()) throw fail(path_, "expected an object, found " + describe(*j_));
  }

  std::string keyPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  Error fail(const std::string& key_path, const std::string& what) const {
    return makeError(origin_, ": ", key_path.empty() ? "(top level)" : key_path, ": ", what);
  }

  static std::string describe(const json& v) {
    std::string s = v.dump();
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return std::string(v.type_name()) + " " + s;
  }

  const json* find(const std::string& key) {
    used_.insert(key);
    if (!j_) return nullptr;
    const auto it = j_->find(key);
    return it == j_->end() ? nullptr : &*it;
  }

  void record(const std::string& key, std::string kind, double lo = 0, double hi = 0,
              std::vector<std::string> choices = {}) {
    if (schema_) schema_->push_back({keyPath(key), std::move(kind), lo, hi, std::move(choices)});
  }

  double numberValue(const json& v, const std::string& key_path, double lo, double hi, bool lo_open) const {
    if (!v.is_number()) throw fail(key_path, "expected a number, found " + describe(v));
    const double x = v.get<double>();
    if (!std::isfinite(x) || (lo_open ? !(x > lo) : !(x >= lo)) || !(x <= hi)) {
      throw fail(key_path, fmt(x) + " is out of range; expected " + (lo_open ? "(" : "[") + fmt(lo) + ", " +
                               fmt(hi) + "]");
    }
    return x;
  }

  double number(const std::string& key, double def, double lo, double hi, bool lo_open = false) {
    record(key, "number", lo, hi);
    const json* v = find(key);
    return v ? numberValue(*v, keyPath(key), lo, hi, lo_open) : def;
  }

  long long integer(const std::string& key, long long def, long long lo, long long hi) {
    record(key, "integer", static_cast<double>(lo), static_cast<double>(hi));
    const json* v = find(key);
    if (!v) return def;
    if (!v->is_number_integer()) throw fail(keyPath(key), "expected an integer, found " + describe(*v));
    const long long x = v->get<long long>();
    if (x < lo || x > hi) {
      throw fail(keyPath(key), std::to_string(x) + " is out of range; expected [" + std::to_string(lo) + ", " +
                                   std::to_string(hi) + "]");
    }
    return x;
  }

  bool boolean(const std::string& key, bool def) {
    record(key, "bool");
    const json* v = find(key);
    if (!v) return def;
    if (!v->is_boolean()) throw fail(keyPath(key), "expected true or false, found " + describe(*v));
    return v->get<bool>();
  }

  std::string string(const std::string& key, const std::string& def) {
    record(key, "string");
    const json* v = find(key);
    if (!v) return def;
    if (!v->is_string()) throw fail(keyPath(key), "expected a string, found " + describe(*v));
    return v->get<std::string>();
  }

  template <typename Enum>
  Enum choice(const std::string& key, Enum def, const std::vector<std::pair<std::string, Enum>>& options) {
    std::vector<std::string> names;
    for (const auto& [name, value] : options) names.push_back(name);
    record(key, "choice", 0, 0, names);
    const json* v = find(key);
    if (!v) return def;
    if (v->is_string()) {
      for (const auto& [name, value] : options) {
        if (v->get<std::string>() == name) return value;
      }
    }
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw fail(keyPath(key), describe(*v) + " is not one of: " + list);
  }

  template <std::size_t N>
  std::array<double, N> numbers(const std::string& key, const std::array<double, N>& def, double lo, double hi,
                                const char* kind = "list") {
    record(key, kind, lo, hi);
    const json* v = find(key);
    if (!v) return def;
    if (!v->is_array() || v->size() != N) {
      throw fail(keyPath(key), "expected a list of " + std::to_string(N) + " numbers, found " + describe(*v));
    }
    std::array<double, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = numberValue((*v)[i], keyPath(key) + "." + std::to_string(i), lo, hi, false);
    return out;
  }

  glm::dvec3 vec3(const std::string& key, const glm::dvec3& def, double lo, double hi, const char* kind = "vec3") {
    const auto a = numbers<3>(key, {def.x, def.y, def.z}, lo, hi, kind);
    return {a[0], a[1], a[2]};
  }

  glm::dvec3 color(const std::string& key, const glm::dvec3& def) { return vec3(key, def, 0.0, 1.0, "color"); }

  Reader child(const std::string& key) { return Reader(find(key), keyPath(key), origin_, schema_); }

  //! Array of objects under `key` (absent: empty).
  std::vector<Reader> list(const std::string& key) {
    const json* v = find(key);
    std::vector<Reader> out;
    if (!v) return out;
    if (!v->is_array()) throw fail(keyPath(key), "expected a list, found " + describe(*v));
    for (std::size_t i = 0; i < v->size(); ++i) out.emplace_back(&(*v)[i], keyPath(key) + "." + std::to_string(i), origin_, schema_);
    return out;
  }

  void finish() const {
    if (!j_) return;
    for (const auto& [key, value] : j_->items()) {
      if (!used_.count(key)) {
        std::string known;
        for (const auto& k : used_) known += (known.empty() ? "" : ", ") + k;
        throw fail(keyPath(key), "unknown key (known here: " + known + ")");
      }
    }
  }

  const std::string& path() const { return path_; }

 private:
  const json* j_;
  std::string path_;
  std::string origin_;
  std::vector<SchemaEntry>* schema_;
  std::set<std::string> used_;
};

constexpr double kBig = 1e9;

LineParams readLines(Reader r) {
  LineParams p;
  p.enabled = r.boolean("enabled", p.enabled);
  p.curvature = r.choice<CurvatureSource>("curvature", p.curvature,
                                          {{"quadric", CurvatureSource::Quadric},
                                           {"cotangent", CurvatureSource::Cotangent},
                                           {"screen", CurvatureSource::Screen}});
  p.curve_factor = r.number("curve_factor", p.curve_factor, 0, 100);
  p.threshold = r.number("threshold", p.threshold, -10, 1);
  p.soft_width = r.number("soft_width", p.soft_width, 0, 1);
  p.line_color = r.color("line_color", p.line_color);
  p.bg_color = r.color("bg_color", p.bg_color);
  p.silhouette = r.number("silhouette", p.silhouette, 0, 1);
  p.depth_edges = r.number("depth_edges", p.depth_edges, 0, 10);
  p.small_object_px = r.number("small_object_px", p.small_object_px, 0, kBig);
  r.finish();
  return p;
}

ShadingParams readShading(Reader r) {
  ShadingParams p;
  p.enabled = r.boolean("enabled", p.enabled);
  p.tones = r.numbers<5>("tones", p.tones, 0, 1);
  p.thresholds = r.numbers<4>("thresholds", p.thresholds, 0, 1);
  for (int k = 1; k < 4; ++k) {
    if (p.thresholds[k] < p.thresholds[k - 1]) {
      throw r.fail(r.keyPath("thresholds"), "t" + std::to_string(k + 1) + " = " + fmt(p.thresholds[k]) +
                                                " is below t" + std::to_string(k) + " = " + fmt(p.thresholds[k - 1]) +
                                                "; expected ascending thresholds");
    }
  }
  p.sigma = r.number("sigma", p.sigma, 0, 1);
  p.beta = r.number("beta", p.beta, -2, 1);
  p.erosion = r.number("erosion", p.erosion, 0, 1);
  p.noise = r.number("noise", p.noise, 0, 1);
  p.noise_scale = r.number("noise_scale", p.noise_scale, 1e-4, 10);
  p.half_lambert = r.boolean("half_lambert", p.half_lambert);
  p.line_value = r.boolean("line_value", p.line_value);
  r.finish();
  return p;
}

WrinkleParams readWrinkle(Reader r) {
  WrinkleParams p;
  p.texture = r.string("texture", p.texture);
  p.inner_tex_factor = r.number("inner_tex_factor", p.inner_tex_factor, 0.01, 100);
  p.repeat = r.number("repeat", p.repeat, 0, 1e4, true);
  p.uv = r.choice<UvSource>("uv", p.uv, {{"mesh", UvSource::Mesh}, {"planar", UvSource::Planar}});
  p.filter = r.choice<TextureFilter>("filter", p.filter, {{"nearest", TextureFilter::Nearest},
                                                          {"bilinear", TextureFilter::Bilinear},
                                                          {"trilinear", TextureFilter::Trilinear}});
  r.finish();
  return p;
}

Object readObject(Reader r) {
  Object o;
  o.name = r.string("name", r.path());
  o.mesh = r.string("mesh", "");
  o.dem = r.string("dem", "");
  if (o.mesh.empty() == o.dem.empty()) {
    throw r.fail(r.path(), o.mesh.empty() ? "needs a 'mesh' or a 'dem' file" : "has both 'mesh' and 'dem'; give one");
  }
  o.z_scale = r.number("z_scale", o.z_scale, 0, 1000, true);
  o.max_vertices = static_cast<std::size_t>(r.integer("max_vertices", static_cast<long long>(o.max_vertices), 4, 100000000));
  o.recentre = r.boolean("recentre", o.recentre);
  {
    Reader t = r.child("transform");
    o.transform.translate = t.vec3("translate", o.transform.translate, -kBig, kBig);
    o.transform.rotate_deg = t.vec3("rotate", o.transform.rotate_deg, -3600, 3600);
    o.transform.scale = t.vec3("scale", o.transform.scale, 1e-6, 1e6);
    t.finish();
  }
  o.spin_deg_per_s = r.number("spin", o.spin_deg_per_s, -36000, 36000);
  o.lines = readLines(r.child("lines"));
  o.shading = readShading(r.child("shading"));
  o.wrinkle = readWrinkle(r.child("wrinkle"));
  r.finish();
  return o;
}

void readCamera(Reader r, Camera& c) {
  if (const json* t = r.find("target"); t && !t->is_null()) {
    c.target = r.vec3("target", {}, -kBig, kBig);
  } else {
    r.record("target", "vec3", -kBig, kBig);
  }
  c.distance = r.number("distance", c.distance, 0, kBig);
  c.azimuth_deg = r.number("azimuth", c.azimuth_deg, -36000, 36000);
  c.elevation_deg = r.number("elevation", c.elevation_deg, -89.9, 89.9);
  c.fov_y_deg = r.number("fov", c.fov_y_deg, 1, 170);
  c.zoom = r.number("zoom", c.zoom, 0.001, 1000);
  for (Reader k : r.list("path")) {
    CameraKey key{c.azimuth_deg, c.elevation_deg, c.zoom};
    key.azimuth_deg = k.number("azimuth", key.azimuth_deg, -36000, 36000);
    key.elevation_deg = k.number("elevation", key.elevation_deg, -89.9, 89.9);
    key.zoom = k.number("zoom", key.zoom, 0.001, 1000);
    k.finish();
    c.path.push_back(key);
  }
  r.finish();
}

Scene parseWith(const json& j, const std::string& origin, const std::filesystem::path& base_dir,
                std::vector<SchemaEntry>* schema) {
  Reader r(&j, "", origin, schema);
  Scene s;
  s.base_dir = base_dir;
  s.seed = static_cast<std::uint64_t>(r.integer("seed", static_cast<long long>(s.seed), 0, (1LL << 53)));
  for (Reader o : r.list("objects")) s.objects.push_back(readObject(std::move(o)));
  if (s.objects.empty() && !schema) throw r.fail("objects", "a scene needs at least one object");
  if (s.objects.size() > 255) {
    throw r.fail("objects", std::to_string(s.objects.size()) + " objects; a scene holds at most 255 (8-bit object ids)");
  }
  {
    Reader l = r.child("light");
    s.light.direction = l.vec3("direction", s.light.direction, -kBig, kBig);
    if (!(glm::length(s.light.direction) > 0)) throw l.fail(l.keyPath("direction"), "must not be zero");
    l.finish();
  }
  readCamera(r.child("camera"), s.camera);
  {
    Reader c = r.child("canvas");
    Canvas& v = s.canvas;
    v.type = c.choice<CanvasType>("type", v.type, {{"none", CanvasType::None}, {"rice_paper", CanvasType::RicePaper},
                                                   {"silk", CanvasType::Silk}, {"static", CanvasType::Static}});
    v.static_pattern = c.choice<CanvasPattern>("static_pattern", v.static_pattern,
                                               {{"rice_paper", CanvasPattern::RicePaper}, {"silk", CanvasPattern::Silk}});
    v.contrast = c.number("contrast", v.contrast, 0, 1);
    v.absorbency = c.number("absorbency", v.absorbency, 0, 1);
    v.grain = c.number("grain", v.grain, 0.5, 256);
    v.frequency = c.number("frequency", v.frequency, 0, 2);
    v.orientation_deg = c.number("orientation", v.orientation_deg, -360, 360);
    v.isotropic = c.boolean("isotropic", v.isotropic);
    v.mix = c.number("mix", v.mix, 0, 1);
    v.perlin_frequency = c.number("perlin_frequency", v.perlin_frequency, 0, 64);
    v.impulses = c.number("impulses", v.impulses, 1, 1024);
    c.finish();
  }
  {
    Reader d = r.child("diffusion");
    Diffusion& f = s.diffusion;
    f.ring_steps = static_cast<int>(d.integer("ring_steps", f.ring_steps, 0, 256));
    f.attenuation = d.number("attenuation", f.attenuation, 0, 1);
    f.absorb = d.number("absorb", f.absorb, 0, 1e3);
    f.residual = d.number("residual", f.residual, 0, 1);
    f.iterations = static_cast<int>(d.integer("iterations", f.iterations, 0, 1000));
    f.threshold = d.number("threshold", f.threshold, 0, 1);
    d.finish();
  }
  {
    Reader o = r.child("output");
    s.output.width = static_cast<int>(o.integer("width", s.output.width, 1, 16384));
    s.output.height = static_cast<int>(o.integer("height", s.output.height, 1, 16384));
    s.output.paper = o.color("paper", s.output.paper);
    s.output.fade = o.number("fade", s.output.fade, 0, 1);
    o.finish();
  }
  r.finish();
  return s;
}

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

json toArray(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

// Deepest nesting of arrays and objects in JSON text (strings skipped), so a value nested
// 100 000 deep is refused before the parser recurses into it.
int jsonDepth(std::string_view text) {
  int depth = 0, deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
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

Scene parseScene(const json& j, const std::string& origin, const std::filesystem::path& base_dir) {
  return parseWith(j, origin, base_dir, nullptr);
}

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
  json j = parseJsonText(readFileBounded(path, kMaxSceneBytes), path.string());
  if (!j.is_object()) {
    throw makeError(path.string(), ": a scene is a JSON object ({...}), found ", j.type_name());
  }
  for (const std::string& o : overrides) applyOverride(j, o);
  return parseScene(j, path.filename().string(), path.parent_path().empty() ? "." : path.parent_path());
}

Scene loadSceneInput(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  std::string ext = path.extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".json") return loadScene(path, overrides);
  const bool mesh = ext == ".obj" || ext == ".ply" || ext == ".off";
  const bool dem = ext == ".dem" || ext == ".asc" || ext == ".png" || ext == ".tif" || ext == ".tiff";
  if (!mesh && !dem) {
    throw makeError(path.string(), ": expected a scene (.json), a mesh (.obj .ply .off) or a heightfield "
                    "(.dem .asc .png .tif)");
  }
  json j = {{"objects", json::array({{{mesh ? "mesh" : "dem", path.string()}, {"name", path.stem().string()}}})}};
  for (const std::string& o : overrides) applyOverride(j, o);
  return parseScene(j, path.filename().string(), ".");
}

json toJson(const Scene& s) {
  json j;
  j["seed"] = s.seed;
  j["objects"] = json::array();
  for (const Object& o : s.objects) {
    json jo;
    jo["name"] = o.name;
    if (!o.mesh.empty()) jo["mesh"] = o.mesh;
    if (!o.dem.empty()) {
      jo["dem"] = o.dem;
      jo["z_scale"] = o.z_scale;
      jo["max_vertices"] = o.max_vertices;
    }
    jo["recentre"] = o.recentre;
    jo["spin"] = o.spin_deg_per_s;
    jo["transform"] = {{"translate", toArray(o.transform.translate)},
                       {"rotate", toArray(o.transform.rotate_deg)},
                       {"scale", toArray(o.transform.scale)}};
    const LineParams& l = o.lines;
    jo["lines"] = {{"enabled", l.enabled},
                   {"curvature", l.curvature == CurvatureSource::Quadric     ? "quadric"
                                  : l.curvature == CurvatureSource::Cotangent ? "cotangent"
                                                                              : "screen"},
                   {"curve_factor", l.curve_factor},
                   {"threshold", l.threshold},
                   {"soft_width", l.soft_width},
                   {"line_color", toArray(l.line_color)},
                   {"bg_color", toArray(l.bg_color)},
                   {"silhouette", l.silhouette},
                   {"depth_edges", l.depth_edges},
                   {"small_object_px", l.small_object_px}};
    const ShadingParams& p = o.shading;
    jo["shading"] = {{"enabled", p.enabled},     {"tones", p.tones},
                     {"thresholds", p.thresholds}, {"sigma", p.sigma},
                     {"beta", p.beta},           {"erosion", p.erosion},
                     {"noise", p.noise},         {"noise_scale", p.noise_scale},
                     {"half_lambert", p.half_lambert}, {"line_value", p.line_value}};
    const WrinkleParams& w = o.wrinkle;
    jo["wrinkle"] = {{"texture", w.texture},
                     {"inner_tex_factor", w.inner_tex_factor},
                     {"repeat", w.repeat},
                     {"uv", w.uv == UvSource::Mesh ? "mesh" : "planar"},
                     {"filter", w.filter == TextureFilter::Nearest    ? "nearest"
                                : w.filter == TextureFilter::Bilinear ? "bilinear"
                                                                      : "trilinear"}};
    j["objects"].push_back(jo);
  }
  j["light"] = {{"direction", toArray(s.light.direction)}};
  const Camera& c = s.camera;
  json jc = {{"target", c.target ? toArray(*c.target) : json(nullptr)},
             {"distance", c.distance},
             {"azimuth", c.azimuth_deg},
             {"elevation", c.elevation_deg},
             {"fov", c.fov_y_deg},
             {"zoom", c.zoom}};
  if (!c.path.empty()) {
    jc["path"] = json::array();
    for (const CameraKey& k : c.path) jc["path"].push_back({{"azimuth", k.azimuth_deg}, {"elevation", k.elevation_deg}, {"zoom", k.zoom}});
  }
  j["camera"] = jc;
  const Canvas& v = s.canvas;
  const char* types[] = {"none", "rice_paper", "silk", "static"};
  j["canvas"] = {{"type", types[static_cast<int>(v.type)]},
                 {"static_pattern", v.static_pattern == CanvasPattern::Silk ? "silk" : "rice_paper"},
                 {"contrast", v.contrast},
                 {"absorbency", v.absorbency},
                 {"grain", v.grain},
                 {"frequency", v.frequency},
                 {"orientation", v.orientation_deg},
                 {"isotropic", v.isotropic},
                 {"mix", v.mix},
                 {"perlin_frequency", v.perlin_frequency},
                 {"impulses", v.impulses}};
  const Diffusion& d = s.diffusion;
  j["diffusion"] = {{"ring_steps", d.ring_steps}, {"attenuation", d.attenuation}, {"absorb", d.absorb},
                    {"residual", d.residual},     {"iterations", d.iterations},   {"threshold", d.threshold}};
  j["output"] = {{"width", s.output.width},
                 {"height", s.output.height},
                 {"paper", toArray(s.output.paper)},
                 {"fade", s.output.fade}};
  return j;
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
  // A file name that is not UTF-8 is written with U+FFFD in its place rather than failing.
  const std::string text = toJson(saved).dump(2, ' ', false, json::error_handler_t::replace) + "\n";
  writeFileAtomically(path, text);
}

const std::vector<SchemaEntry>& sceneSchema() {
  static const std::vector<SchemaEntry> schema = [] {
    std::vector<SchemaEntry> entries;
    const json probe = {{"objects", json::array({{{"dem", "x"}}})}, {"camera", {{"path", json::array({json::object()})}}}};
    parseWith(probe, "schema", ".", &entries);
    for (SchemaEntry& e : entries) {
      for (const char* prefix : {"objects.0.", "camera.path.0."}) {
        const std::string p(prefix);
        if (e.path.rfind(p, 0) == 0) e.path = p.substr(0, p.size() - 2) + "*." + e.path.substr(p.size());
      }
    }
    return entries;
  }();
  return schema;
}

}  // namespace shanshui::scene
