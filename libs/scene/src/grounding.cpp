// Objects standing on other objects: the pose that rests a model's base on the ground under
// it, and the spots a rule finds on the ground's form (grounding.h).
#include "shanshui/scene/grounding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include "scene_params.h"
#include "shanshui/core/error.h"

namespace shanshui::scene {

namespace {

std::string number(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

std::string label(const Scene& s, std::size_t i) {
  return s.objects[i].name.empty() ? "objects." + std::to_string(i) : "'" + s.objects[i].name + "'";
}

std::vector<std::size_t> namedLike(const Scene& s, const std::string& name) {
  std::vector<std::size_t> found;
  for (std::size_t k = 0; k < s.objects.size(); ++k)
    if (s.objects[k].name == name) found.push_back(k);
  return found;
}

mesh::Bounds transformed(const mesh::Bounds& b, const glm::dmat4& m) {
  mesh::Bounds out{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 w(m * glm::dvec4(b.corner(c), 1.0));
    out.min = glm::min(out.min, w);
    out.max = glm::max(out.max, w);
  }
  return out;
}

// The ground's surface seen from the world: heights and normals at world (x, y), through
// its (untilted) model matrix.
struct Ground {
  const elements::Terrain& terrain;
  glm::dmat4 to_world, to_model;

  std::optional<double> height(double x, double y) const {
    const glm::dvec3 m(to_model * glm::dvec4(x, y, 0.0, 1.0));
    glm::dvec3 p;
    double slope = 0.0;
    if (!terrain.surface(m.x, m.y, p, slope)) return std::nullopt;
    return (to_world * glm::dvec4(p, 1.0)).z;
  }
  glm::dvec3 normal(double x, double y, double h) const {
    const auto e = height(x + h, y), w = height(x - h, y), n = height(x, y + h), s = height(x, y - h);
    if (!e || !w || !n || !s) return {0.0, 0.0, 1.0};
    return glm::normalize(glm::dvec3(-(*e - *w) / (2.0 * h), -(*n - *s) / (2.0 * h), 1.0));
  }
  elements::Site site(double x, double y) const {
    const glm::dvec3 m(to_model * glm::dvec4(x, y, 0.0, 1.0));
    return terrain.site(m.x, m.y);
  }
};

// The object's pose without its translation, and what it covers: the model box's centre
// and horizontal half-extents under it, its height.
struct Footprint {
  glm::dvec3 centre{0.0};
  glm::dvec2 half{0.0};
  double height = 0.0;
  double radius() const { return glm::length(half); }
};

Footprint footprint(const mesh::Bounds& model, const glm::dmat4& pose) {
  const mesh::Bounds b = transformed(model, pose);
  return {glm::dvec3(pose * glm::dvec4(model.centre(), 1.0)), 0.5 * glm::dvec2(b.size()), b.size().z};
}

struct Placed {
  glm::dvec2 at;
  double radius;
  GroundSite site;
};

// How well a spot suits a site rule; lowest() where it does not at all.
double siteScore(GroundSite rule, const elements::Site& s, double z, double level, double relief, double steep_near) {
  constexpr double kNo = std::numeric_limits<double>::lowest();
  const double above = (z - level) / std::max(relief, 1e-12);  // fraction of the ground's relief
  switch (rule) {
    case GroundSite::Summit:
      return s.slope_deg > 25.0 || above < 0.0 ? kNo : s.height - s.slope_deg / 300.0;
    case GroundSite::Ridge:
      return s.slope_deg > 25.0 || above < 0.02 ? kNo : s.ridge + 0.6 * s.height - s.slope_deg / 100.0;
    case GroundSite::WaterEdge: {
      if (above < -0.01) return kNo;
      const double d = above / 0.01;
      return std::exp(-d * d) - s.slope_deg / 200.0;
    }
    case GroundSite::Bank:
      if (s.slope_deg > 15.0 || above < 0.004 || above > 0.15) return kNo;
      return 0.5 * s.floor + 0.5 * (1.0 - s.slope_deg / 15.0) + 0.5 * (1.0 - above / 0.15);
    case GroundSite::SlopeFoot:
      if (s.slope_deg > 20.0 || above < 0.004) return kNo;
      return std::min(steep_near / 35.0, 1.0) + 0.5 * s.hollow + 0.3 * (1.0 - s.height) - s.slope_deg / 40.0;
    case GroundSite::At:
      break;
  }
  return kNo;
}

const char* siteName(GroundSite site) {
  for (const auto& [name, value] : kGroundSites)
    if (value == site) return name;
  return "?";
}

struct Candidate {
  double score;
  glm::dvec2 at;  //!< world x, y
};

// The spots of a grid over the ground (96 × 96, inside its dissolving border's band, where
// its land is drawn) that suit `rule`, best first.
std::vector<Candidate> rankSites(GroundSite rule, const Object& ground_object, const mesh::Bounds& model,
                                 const Ground& ground, const glm::dmat4& to_world, double level) {
  const mesh::Bounds world = transformed(model, to_world);
  const glm::dvec3 half = 0.5 * model.size();
  const double band = ground_object.dissolvesBorder() ? ground_object.border.width * std::min(half.x, half.y) : 0.0;
  const glm::dvec3 lo = model.min + glm::dvec3(band, band, 0), hi = model.max - glm::dvec3(band, band, 0);
  const double reach = 0.04 * std::max(world.size().x, world.size().y);  // a slope foot's steep neighbours
  constexpr int n = 96;
  std::vector<Candidate> candidates;
  for (int yi = 0; yi < n; ++yi) {
    for (int xi = 0; xi < n; ++xi) {
      const glm::dvec3 m(lo.x + (xi + 0.5) / n * (hi.x - lo.x), lo.y + (yi + 0.5) / n * (hi.y - lo.y), 0.0);
      const glm::dvec2 w(to_world * glm::dvec4(m, 1.0));
      const std::optional<double> z = ground.height(w.x, w.y);
      if (!z) continue;
      double steep = 0.0;
      if (rule == GroundSite::SlopeFoot) {
        for (int k = 0; k < 8; ++k) {
          const double a = k * std::numbers::pi / 4.0;
          steep = std::max(steep, ground.site(w.x + reach * std::cos(a), w.y + reach * std::sin(a)).slope_deg);
        }
      }
      const double score = siteScore(rule, ground.site(w.x, w.y), *z, level, world.size().z, steep);
      if (score > std::numeric_limits<double>::lowest()) candidates.push_back({score, w});
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.score > y.score; });
  return candidates;
}

}  // namespace

std::optional<std::size_t> groundOf(const Scene& s, std::size_t i) {
  if (!s.objects[i].grounded()) return std::nullopt;
  const std::vector<std::size_t> found = namedLike(s, s.objects[i].ground.on);
  if (found.size() != 1 || found[0] == i) return std::nullopt;
  return found[0];
}

bool floatsOnWater(const Scene& s, std::size_t i) {
  const Object& o = s.objects[i];
  return o.ground.on == kOnWater && s.usesWater() && namedLike(s, kOnWater).empty();
}

std::string groundingProblem(const Scene& s) {
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    if (!o.grounded()) continue;
    const std::string key = "objects." + std::to_string(i) + ".ground.on: '" + o.ground.on + "' ";
    const std::vector<std::size_t> found = namedLike(s, o.ground.on);
    if (found.empty() && o.ground.on == kOnWater) {
      if (!s.usesWater()) return key + "needs water (water.enabled: true)";
      if (o.ground.site != GroundSite::At) return key + "floats at transform.translate's x, y: its site must be 'at'";
      continue;
    }
    if (found.empty()) {
      std::string names;
      for (const Object& other : s.objects)
        if (!other.name.empty()) names += (names.empty() ? "" : ", ") + ("'" + other.name + "'");
      return key + "names no object (named objects: " + (names.empty() ? "none" : names) + ")";
    }
    if (found.size() > 1) return key + "names " + std::to_string(found.size()) + " objects; names must be unique";
    if (found[0] == i) return key + "is this object itself";
    const Object& g = s.objects[found[0]];
    if (g.grounded()) return key + "stands on another object itself; a ground must stand on nothing";
    if (g.animated()) return key + "moves (spin, velocity or path); a ground must stand still";
  }
  return "";
}

bool usesGrounding(const Scene& s) {
  return std::any_of(s.objects.begin(), s.objects.end(), [](const Object& o) { return o.grounded(); });
}

mesh::Bounds baseBounds(const Scene& s, const std::vector<mesh::Bounds>& model_bounds) {
  mesh::Bounds b{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    if (s.objects[i].grounded()) continue;
    const mesh::Bounds w = transformed(model_bounds[i], s.objects[i].transform.matrix());
    b.min = glm::min(b.min, w.min);
    b.max = glm::max(b.max, w.max);
  }
  return b;
}

double waterHeight(const Scene& s, const mesh::Bounds& base) {
  if (!s.usesWater()) return std::numeric_limits<double>::lowest();
  return base.min.z + s.water.level * base.size().z;
}

Grounding::Grounding(const std::vector<LoadedObject>& objects) {
  for (const LoadedObject& o : objects) geometry_.push_back(o.geometry);
}

const elements::Terrain& Grounding::terrain(std::size_t ground) const {
  auto& t = terrains_[ground];
  if (!t) t = std::make_unique<elements::Terrain>(geometry_[ground]->mesh);
  return *t;
}

std::vector<glm::dmat4> Grounding::worldMatrices(const Scene& s) const {
  SHANSHUI_CHECK_EQ(geometry_.size(), s.objects.size());
  std::vector<glm::dmat4> world;
  std::vector<mesh::Bounds> model_bounds;
  for (const auto& g : geometry_) model_bounds.push_back(g->bounds);
  for (const Object& o : s.objects) world.push_back(o.transform.matrix());
  if (const std::string problem = groundingProblem(s); !problem.empty()) throw makeError(problem);
  const double level = waterHeight(s, baseBounds(s, model_bounds));
  std::map<std::size_t, std::vector<Placed>> placed;  // per ground, in object order

  for (std::size_t i = 0; i < s.objects.size(); ++i) {
    const Object& o = s.objects[i];
    if (floatsOnWater(s, i)) {
      // On the water: its lowest point `sink` of its height below the surface.
      const mesh::Bounds b = transformed(model_bounds[i], world[i]);
      world[i] =
          glm::translate(glm::dmat4(1.0),
                         glm::dvec3(0.0, 0.0, level - o.ground.sink * b.size().z - b.min.z + o.transform.translate.z)) *
          world[i];
      continue;
    }
    const std::optional<std::size_t> gi = groundOf(s, i);
    if (!gi) continue;
    const std::string key = "objects." + std::to_string(i) + ".ground";
    const glm::dmat4& tg = world[*gi];
    // The ground must keep its vertical vertical: rotations about z and scales only.
    const glm::dvec3 gx(tg[0]), gy(tg[1]), gz(tg[2]);
    const double tol = 1e-6 * std::max({glm::length(gx), glm::length(gy), glm::length(gz)});
    if (std::abs(gx.z) > tol || std::abs(gy.z) > tol || std::abs(gz.x) > tol || std::abs(gz.y) > tol || gz.z <= 0.0)
      throw makeError(key, ".on: ", label(s, *gi),
                      " is tilted (transform.rotate about x or y); an object can stand only on a level ground");
    const Ground ground{terrain(*gi), tg, glm::inverse(tg)};
    const mesh::Bounds gb = transformed(model_bounds[*gi], tg);
    const double relief = gb.size().z;

    Transform pose_only = o.transform;
    pose_only.translate = glm::dvec3(0.0);
    const glm::dmat4 pose = pose_only.matrix();
    const Footprint fp = footprint(model_bounds[i], pose);
    auto fits = [&](glm::dvec2 at) {
      // Objects found by the same rule may stand close (boulders in a group at the water);
      // a different rule keeps its distance (the pavilion is not the pagoda's neighbour).
      for (const Placed& p : placed[*gi]) {
        const double apart = (p.site == o.ground.site ? 0.01 : 0.08) * std::max(gb.size().x, gb.size().y);
        if (glm::distance(at, p.at) < 1.2 * (fp.radius() + p.radius) + apart) return false;
      }
      for (int c = 0; c < 4; ++c)
        if (!ground.height(at.x + (c & 1 ? 1 : -1) * fp.half.x, at.y + (c & 2 ? 1 : -1) * fp.half.y)) return false;
      return true;
    };

    glm::dvec2 at(o.transform.translate);
    if (o.ground.site != GroundSite::At) {
      if ((o.ground.site == GroundSite::WaterEdge || o.ground.site == GroundSite::Bank) && !s.usesWater())
        throw makeError(key, ".site: '", siteName(o.ground.site), "' needs water (water.enabled: true)");
      const std::vector<Candidate> candidates =
          rankSites(o.ground.site, s.objects[*gi], model_bounds[*gi], ground, tg, level);
      const auto best =
          std::find_if(candidates.begin(), candidates.end(), [&](const Candidate& c) { return fits(c.at); });
      if (best == candidates.end())
        throw makeError(key, ".site: no spot on ", label(s, *gi), " suits '", siteName(o.ground.site),
                        "' and leaves room for the objects placed there before (", placed[*gi].size(),
                        "); it spans z [", gb.min.z, ", ", gb.max.z, "]",
                        s.usesWater() ? ", the water is at z " + number(level) : "");
      at = best->at;
    }

    const std::optional<double> centre_z = ground.height(at.x, at.y);
    if (!centre_z)
      throw makeError(key, ": (", at.x, ", ", at.y, ") from transform.translate is off ", label(s, *gi),
                      ", which covers x [", gb.min.x, ", ", gb.max.x, "], y [", gb.min.y, ", ", gb.max.y, "]");
    // Upright, the base goes down to the lowest ground under the footprint (nothing floats
    // on a slope); tilted to the slope, the centre's height is the ground's under all of it.
    double lowest = *centre_z;
    for (int c = 0; c < 8; ++c) {
      const double a = c * std::numbers::pi / 4.0;
      if (const auto z = ground.height(at.x + fp.half.x * std::cos(a), at.y + fp.half.y * std::sin(a)))
        lowest = std::min(lowest, *z);
    }
    const glm::dvec3 up(0.0, 0.0, 1.0);
    const glm::dvec3 n = ground.normal(at.x, at.y, std::max(0.5 * fp.radius(), 1e-6 * std::max(relief, 1.0)));
    glm::dmat4 tilt(1.0);
    const glm::dvec3 axis = glm::cross(up, n);
    if (glm::length(axis) > 1e-9 && o.ground.align > 0.0)
      tilt = glm::rotate(glm::dmat4(1.0), o.ground.align * std::acos(std::clamp(n.z, -1.0, 1.0)), glm::normalize(axis));
    const glm::dmat4 posed = tilt * pose;
    const mesh::Bounds b = transformed(model_bounds[i], posed);
    // Upright, the box's lowest point meets the lowest ground and its centre stands over
    // (x, y); tilted, the centre of its base sits on the ground at (x, y).
    const double a = o.ground.align;
    const glm::dvec3 c(posed * glm::dvec4(model_bounds[i].centre(), 1.0));
    const glm::dvec3 foot(
        posed * glm::dvec4(model_bounds[i].centre().x, model_bounds[i].centre().y, model_bounds[i].min.z, 1.0));
    const glm::dvec3 anchor((1.0 - a) * glm::dvec2(c) + a * glm::dvec2(foot), (1.0 - a) * b.min.z + a * foot.z);
    const double base = a * *centre_z + (1.0 - a) * lowest - o.ground.sink * b.size().z;
    world[i] = glm::translate(glm::dmat4(1.0),
                              glm::dvec3(at.x - anchor.x, at.y - anchor.y, base - anchor.z + o.transform.translate.z)) *
               posed;
    placed[*gi].push_back({at, fp.radius(), o.ground.site});
  }
  return world;
}

}  // namespace shanshui::scene
