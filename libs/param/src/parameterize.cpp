#include "shanshui/param/parameterize.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>

#include "cgal_methods.h"
#include "shanshui/core/error.h"
#include "shanshui/param/seam_cut.h"

namespace shanshui::param {
namespace {

using Clock = std::chrono::steady_clock;

const std::pair<Method, const char*> kMethodNames[] = {
    {Method::Auto, "auto"},   {Method::Xy, "xy"},     {Method::Mvc, "mvc"},   {Method::Dcm, "dcm"},
    {Method::Tutte, "tutte"}, {Method::Lscm, "lscm"}, {Method::Arap, "arap"}, {Method::Authalic, "authalic"},
};

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

int findRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Border loops and edge count of a triangle mesh, from one sorted list of undirected edges
// (an edge used by one triangle is a border edge).
struct Topology {
  int border_loops = 0;
  std::size_t edges = 0;
};

Topology topology(const mesh::Mesh& m) {
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * m.triangles.size());
  for (const glm::uvec3& t : m.triangles) {
    keys.push_back(edgeKey(t.x, t.y));
    keys.push_back(edgeKey(t.y, t.z));
    keys.push_back(edgeKey(t.z, t.x));
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> onBorder(m.positions.size(), false);
  Topology top;
  for (std::size_t e = 0; e < keys.size();) {
    std::size_t f = e + 1;
    while (f < keys.size() && keys[f] == keys[e]) ++f;
    ++top.edges;
    if (f - e == 1) {
      const int a = static_cast<int>(keys[e] >> 32), b = static_cast<int>(keys[e] & 0xffffffffu);
      onBorder[a] = onBorder[b] = true;
      parent[findRoot(parent, a)] = findRoot(parent, b);
    }
    e = f;
  }
  for (std::size_t v = 0; v < parent.size(); ++v) {
    top.border_loops += onBorder[v] && findRoot(parent, static_cast<int>(v)) == static_cast<int>(v);
  }
  return top;
}

std::vector<glm::dvec2> runMethod(const mesh::Mesh& m, Method method, const ParamOptions& opts) {
  switch (method) {
    case Method::Xy: {
      std::vector<glm::dvec2> uv(m.positions.size());
      for (std::size_t i = 0; i < uv.size(); ++i) uv[i] = {m.positions[i].x, m.positions[i].y};
      return uv;
    }
    case Method::Mvc:
    case Method::Dcm:
    case Method::Tutte:
    case Method::Authalic:
      return detail::fixedBorderUvs(m, method, opts.border, opts.authalic_iterations);
    case Method::Lscm:
    case Method::Arap:
      return detail::freeBorderUvs(m, method);
    case Method::Auto:
      break;
  }
  SHANSHUI_CHECK(false);
  return {};
}

// Runs one method and measures it; UVs are made counter-clockwise (mirrored in v if the
// method produced a clockwise map) so "flipped" means folded, not mirrored.
MethodTrial tryMethod(const mesh::Mesh& m, Method method, const ParamOptions& opts, mesh::Mesh* result) {
  MethodTrial trial;
  trial.method = method;
  const auto start = Clock::now();
  std::vector<glm::dvec2> uv;
  try {
    uv = runMethod(m, method, opts);
  } catch (const Error& e) {
    trial.note = e.what();
    trial.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return trial;
  }
  trial.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  trial.ran = true;
  double signedArea = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec2 a = uv[t.x], b = uv[t.y], c = uv[t.z];
    signedArea += (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
  }
  *result = m;
  result->uvs.resize(uv.size());
  for (std::size_t i = 0; i < uv.size(); ++i) {
    result->uvs[i] = glm::vec2(static_cast<float>(uv[i].x), static_cast<float>(signedArea < 0 ? -uv[i].y : uv[i].y));
  }
  trial.distortion = measureDistortion(*result);
  return trial;
}

std::string describe(const Distortion& d) {
  std::ostringstream s;
  s << d.flipped << " flipped, " << d.degenerate << " degenerate and " << d.non_finite << " non-finite UV faces";
  return s.str();
}

}  // namespace

const char* methodName(Method m) {
  for (const auto& [method, name] : kMethodNames)
    if (method == m) return name;
  return "?";
}

Method parseMethod(const std::string& text) {
  for (const auto& [method, name] : kMethodNames)
    if (text == name) return method;
  throw makeError("--method: unknown method '", text, "'; expected auto, xy, mvc, dcm, tutte, lscm, arap or authalic");
}

const char* borderName(Border b) {
  return b == Border::Square ? "square" : "circle";
}

Border parseBorder(const std::string& text) {
  if (text == "circle") return Border::Circle;
  if (text == "square") return Border::Square;
  throw makeError("--border: unknown border '", text, "'; expected circle or square");
}

int borderLoops(const mesh::Mesh& m) {
  return topology(m).border_loops;
}

mesh::Mesh parameterize(const mesh::Mesh& input, const ParamOptions& opts, ParamReport* report,
                        const std::string& what) {
  if (opts.authalic_iterations < 1 || opts.authalic_iterations > 1000) {
    throw makeError("authalic iterations ", opts.authalic_iterations, "; expected [1, 1000]");
  }
  if (!(opts.auto_accept_stretch >= 1.0)) {
    throw makeError("auto stretch limit ", opts.auto_accept_stretch, "; expected at least 1");
  }
  if (input.triangles.empty()) throw makeError(what, ": no triangles to parameterize");
  for (const glm::dvec3& p : input.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw makeError(what, ": NaN or infinite vertex coordinates; repair the mesh first");
  }
  // A closed sphere-like mesh is cut open along one seam first.
  mesh::Mesh disc;
  int seamVertices = 0;
  Topology top = topology(input);
  if (top.border_loops == 0) {
    SeamCut cut = cutOpen(input, what);
    disc = std::move(cut.mesh);
    seamVertices = static_cast<int>(cut.seam.size());
    top = topology(disc);
  } else {
    disc = input;
  }
  if (top.border_loops > 1) {
    throw makeError(what, ": ", top.border_loops,
                    " border loops (holes or several components); fill the holes "
                    "and keep one component first (shanshui-repair)");
  }
  const long long euler = static_cast<long long>(disc.positions.size()) - static_cast<long long>(top.edges) +
                          static_cast<long long>(disc.triangles.size());
  if (euler != 1) {
    throw makeError(what, ": not a topological disc (Euler characteristic ", euler,
                    ", expected 1: handles or several components); parameterization needs a disc");
  }

  // Recentre in double: UTM-sized coordinates would lose precision in the solvers.
  mesh::Mesh m = disc;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : m.positions) centre += p;
  centre /= static_cast<double>(m.positions.size());
  for (glm::dvec3& p : m.positions) p -= centre;

  const auto start = Clock::now();
  ParamReport local;
  ParamReport& r = report ? *report : local;
  r = {};
  r.seam_vertices = seamVertices;
  const int vertices = static_cast<int>(m.positions.size());
  mesh::Mesh best;
  bool haveBest = false;
  auto consider = [&](Method method) {
    mesh::Mesh result;
    MethodTrial trial = tryMethod(m, method, opts, &result);
    const bool better =
        trial.ran && trial.distortion.valid() && (!haveBest || trial.distortion.l2_stretch < r.distortion.l2_stretch);
    if (better) {
      best = std::move(result);
      haveBest = true;
      r.method = method;
      r.distortion = trial.distortion;
    }
    r.trials.push_back(std::move(trial));
  };

  if (opts.method != Method::Auto) {
    consider(opts.method);
    const MethodTrial& t = r.trials.back();
    if (!t.ran) throw makeError(what, ": ", t.note);
    if (!haveBest) {
      throw makeError(what, ": ", methodName(opts.method), " gives ", describe(t.distortion), " of ",
                      t.distortion.faces, "; try --method auto");
    }
  } else {
    consider(Method::Xy);
    const std::pair<Method, int> plan[] = {{Method::Mvc, opts.auto_max_vertices_linear},
                                           {Method::Lscm, opts.auto_max_vertices_linear},
                                           {Method::Arap, opts.auto_max_vertices_arap}};
    for (const auto& [method, limit] : plan) {
      // Near-isometric already (the projection on a heightfield, LSCM on a developable
      // surface): the slower methods cannot do much better.
      const bool good = haveBest && r.distortion.l2_stretch <= opts.auto_accept_stretch;
      if (good || vertices > limit) {
        MethodTrial skipped;
        skipped.method = method;
        std::ostringstream why;
        if (good) {
          why << "skipped: " << methodName(r.method)
              << " is already valid with L2 stretch <= " << opts.auto_accept_stretch;
        } else {
          why << "skipped: " << vertices << " vertices > " << limit;
        }
        skipped.note = why.str();
        r.trials.push_back(skipped);
        continue;
      }
      consider(method);
    }
    // Last resort: Tutte's barycentric map onto a convex border is one-to-one in exact
    // arithmetic (Tutte 1963, Floater 2003), whatever the mesh.
    if (!haveBest && vertices <= opts.auto_max_vertices_linear) consider(Method::Tutte);
    if (!haveBest) {
      std::ostringstream s;
      for (const MethodTrial& t : r.trials) {
        s << "; " << methodName(t.method) << ": " << (t.ran ? describe(t.distortion) : t.note);
      }
      throw makeError(what, ": no method gave a one-to-one parameterization", s.str());
    }
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  best.positions = disc.positions;  // the caller's coordinates (plus seam copies)
  return best;
}

}  // namespace shanshui::param
