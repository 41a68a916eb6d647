#include "shanshui/param/charts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "cgal_methods.h"
#include "shanshui/core/error.h"
#include "shanshui/core/parallel_for.h"

namespace shanshui::param {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

double cross2(glm::dvec2 a, glm::dvec2 b) {
  return a.x * b.y - a.y * b.x;
}

// A set of the input's faces as a mesh of its own. Around each vertex the chart's faces are
// grouped into fans joined through chart edges; each fan gets its own copy, so two parts
// that touch only at a vertex come apart and the result is always manifold.
struct ChartMesh {
  mesh::Mesh mesh;
  std::vector<std::uint32_t> source_vertex;  // per chart vertex
  std::vector<std::uint32_t> faces;          // input face per chart face
  int components = 0;                        // edge-connected pieces
  std::vector<int> component_of_face;
};

ChartMesh extract(const mesh::Mesh& m, const std::vector<std::uint32_t>& faces) {
  ChartMesh c;
  c.faces = faces;
  const std::size_t nf = faces.size();
  UnionFind corners(3 * nf), pieces(nf);
  std::unordered_map<std::uint64_t, std::uint32_t> firstCorner;  // edge -> corner of its smaller end
  firstCorner.reserve(3 * nf);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const glm::uvec3 t = m.triangles[faces[i]];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      const std::uint32_t ca = 3 * i + k, cb = 3 * i + (k + 1) % 3;
      const auto [it, inserted] = firstCorner.emplace(edgeKey(a, b), a < b ? ca : cb);
      if (inserted) continue;
      // The same edge in an earlier face: join the corners at both of its ends.
      const std::uint32_t other = it->second, otherFace = other / 3;
      const glm::uvec3 u = m.triangles[faces[otherFace]];
      const std::uint32_t lo = a < b ? ca : cb, hi = a < b ? cb : ca;
      const std::uint32_t hiVertex = std::max(a, b);
      const std::uint32_t otherHi = 3 * otherFace + (u.x == hiVertex ? 0 : u.y == hiVertex ? 1 : 2);
      corners.join(lo, other);
      corners.join(hi, otherHi);
      pieces.join(i, otherFace);
    }
  }
  std::unordered_map<std::uint32_t, std::uint32_t> vertexOfRoot;
  c.mesh.triangles.resize(nf);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const glm::uvec3 t = m.triangles[faces[i]];
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] =
          vertexOfRoot.emplace(corners.find(3 * i + k), static_cast<std::uint32_t>(c.source_vertex.size()));
      if (inserted) {
        c.source_vertex.push_back(t[k]);
        c.mesh.positions.push_back(m.positions[t[k]]);
      }
      c.mesh.triangles[i][k] = it->second;
    }
  }
  std::unordered_map<std::uint32_t, int> componentOfRoot;
  c.component_of_face.resize(nf);
  for (std::uint32_t i = 0; i < nf; ++i) {
    const auto [it, inserted] = componentOfRoot.emplace(pieces.find(i), c.components);
    c.components += inserted;
    c.component_of_face[i] = it->second;
  }
  return c;
}

// One border loop and Euler characteristic 1. The chart is manifold, so border edges form
// simple loops and every border vertex has exactly one outgoing border edge.
bool isDisc(const mesh::Mesh& m) {
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(3 * m.triangles.size());
  for (const glm::uvec3& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++uses[edgeKey(t[k], t[(k + 1) % 3])];
  UnionFind loops(m.positions.size());
  std::vector<bool> onBorder(m.positions.size(), false);
  for (const auto& [key, n] : uses) {
    if (n > 2) return false;
    if (n != 1) continue;
    const auto a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
    onBorder[a] = onBorder[b] = true;
    loops.join(a, b);
  }
  int borderLoops = 0;
  for (std::uint32_t v = 0; v < m.positions.size(); ++v) borderLoops += onBorder[v] && loops.find(v) == v;
  const long long euler = static_cast<long long>(m.positions.size()) - static_cast<long long>(uses.size()) +
                          static_cast<long long>(m.triangles.size());
  return borderLoops == 1 && euler == 1;
}

double surfaceArea(const mesh::Mesh& m) {
  double a = 0.0;
  for (const glm::uvec3& t : m.triangles)
    a += 0.5 * glm::length(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
  return a;
}

// True when two border edges of the flattened chart cross: the chart overlaps itself
// although every face keeps its orientation (a spiral, a map that wraps round).
bool borderCrosses(const mesh::Mesh& m, const std::vector<glm::dvec2>& uv) {
  std::unordered_map<std::uint64_t, int> uses;
  for (const glm::uvec3& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++uses[edgeKey(t[k], t[(k + 1) % 3])];
  std::vector<std::pair<std::uint32_t, std::uint32_t>> border;
  for (const auto& [key, n] : uses)
    if (n == 1)
      border.emplace_back(static_cast<std::uint32_t>(key >> 32), static_cast<std::uint32_t>(key & 0xffffffffu));
  std::sort(border.begin(), border.end(), [&](const auto& a, const auto& b) {
    return std::min(uv[a.first].x, uv[a.second].x) < std::min(uv[b.first].x, uv[b.second].x);
  });
  for (std::size_t i = 0; i < border.size(); ++i) {
    const glm::dvec2 p = uv[border[i].first], q = uv[border[i].second];
    const double maxX = std::max(p.x, q.x);
    for (std::size_t j = i + 1; j < border.size(); ++j) {
      const glm::dvec2 r = uv[border[j].first], s = uv[border[j].second];
      if (std::min(r.x, s.x) > maxX) break;  // sorted by left end: no later edge reaches back
      if (border[i].first == border[j].first || border[i].first == border[j].second ||
          border[i].second == border[j].first || border[i].second == border[j].second)
        continue;
      const double d1 = cross2(q - p, r - p), d2 = cross2(q - p, s - p);
      const double d3 = cross2(s - r, p - r), d4 = cross2(s - r, q - r);
      if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0) return true;
    }
  }
  return false;
}

struct Flattened {
  std::vector<glm::dvec2> uv;
  Distortion distortion;
  const char* method = "";
  bool ok = false;  // one-to-one: valid faces and no border crossing
};

// Counter-clockwise, UV area = surface area, measured.
Flattened finish(const mesh::Mesh& chart, std::vector<glm::dvec2> uv, const char* method, double area3) {
  Flattened f;
  f.method = method;
  double signedArea = 0.0;
  for (const glm::uvec3& t : chart.triangles) signedArea += cross2(uv[t.y] - uv[t.x], uv[t.z] - uv[t.x]);
  const double k = std::abs(signedArea) > 0 ? std::sqrt(2.0 * area3 / std::abs(signedArea)) : 1.0;
  for (glm::dvec2& p : uv) p = glm::dvec2(p.x, signedArea < 0 ? -p.y : p.y) * k;
  mesh::Mesh measured;
  measured.positions = chart.positions;
  measured.triangles = chart.triangles;
  measured.uvs.assign(uv.begin(), uv.end());
  f.distortion = measureDistortion(measured);
  f.ok = f.distortion.valid() && !borderCrosses(chart, uv);
  f.uv = std::move(uv);
  return f;
}

// Projection onto the plane of the chart's area-weighted normal, then LSCM when that is not
// one-to-one or stretches more than `limit`; the better of the two.
Flattened flatten(const mesh::Mesh& chart, double limit) {
  const double area3 = surfaceArea(chart);
  glm::dvec3 normal(0.0), centre(0.0);
  for (const glm::uvec3& t : chart.triangles)
    normal += glm::cross(chart.positions[t.y] - chart.positions[t.x], chart.positions[t.z] - chart.positions[t.x]);
  for (const glm::dvec3& p : chart.positions) centre += p / static_cast<double>(chart.positions.size());
  Flattened best;
  if (glm::length(normal) > 1e-9 * area3) {
    const glm::dvec3 n = glm::normalize(normal);
    const glm::dvec3 e1 =
        glm::normalize(std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0)) : glm::cross(n, glm::dvec3(0, 1, 0)));
    const glm::dvec3 e2 = glm::cross(n, e1);
    std::vector<glm::dvec2> uv(chart.positions.size());
    for (std::size_t i = 0; i < uv.size(); ++i) {
      const glm::dvec3 d = chart.positions[i] - centre;
      uv[i] = {glm::dot(d, e1), glm::dot(d, e2)};
    }
    best = finish(chart, std::move(uv), "plane", area3);
    if (best.ok && best.distortion.l2_stretch <= limit) return best;
  }
  if (chart.triangles.size() >= 2) {
    try {
      Flattened lscm = finish(chart, detail::freeBorderUvs(chart, Method::Lscm), "lscm", area3);
      if (lscm.ok && (!best.ok || lscm.distortion.l2_stretch < best.distortion.l2_stretch)) best = std::move(lscm);
    } catch (const Error&) {
      // LSCM refused the chart (CGAL's status): keep the projection's verdict.
    }
  }
  return best;
}

double boxAngle(const std::vector<glm::dvec2>& uv);
glm::dvec2 orient(std::vector<glm::dvec2>& uv, double angle);

// UV area over the area of the least rectangle round the chart: what packing can reach.
double boxFill(const mesh::Mesh& chart, std::vector<glm::dvec2> uv) {
  const glm::dvec2 box = orient(uv, boxAngle(uv));
  double area = 0.0;
  for (const glm::uvec3& t : chart.triangles) area += 0.5 * std::abs(cross2(uv[t.y] - uv[t.x], uv[t.z] - uv[t.x]));
  return box.x * box.y > 0 ? area / (box.x * box.y) : 1.0;
}

// Halves of a flattened chart across the long side of its least rectangle, by face area:
// a long or branching chart becomes two that pack better.
std::vector<std::vector<std::uint32_t>> splitAcross(const ChartMesh& c, std::vector<glm::dvec2> uv) {
  orient(uv, boxAngle(uv));
  glm::dvec2 hi(0.0);
  for (const glm::dvec2& p : uv) hi = glm::max(hi, p);
  const int axis = hi.x >= hi.y ? 0 : 1;
  std::vector<std::pair<double, std::uint32_t>> order;
  double total = 0.0;
  for (std::uint32_t i = 0; i < c.mesh.triangles.size(); ++i) {
    const glm::uvec3 t = c.mesh.triangles[i];
    order.emplace_back((uv[t.x][axis] + uv[t.y][axis] + uv[t.z][axis]) / 3.0, i);
  }
  std::sort(order.begin(), order.end());
  std::vector<double> area(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const glm::uvec3 t = c.mesh.triangles[order[k].second];
    area[k] = 0.5 * std::abs(cross2(uv[t.y] - uv[t.x], uv[t.z] - uv[t.x]));
    total += area[k];
  }
  std::vector<std::vector<std::uint32_t>> parts(2);
  double sum = 0.0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const bool second = sum >= 0.5 * total && !parts[0].empty();
    parts[second ? 1 : 0].push_back(c.faces[order[k].second]);
    sum += area[k];
  }
  if (parts[1].empty()) {
    parts[1].push_back(parts[0].back());
    parts[0].pop_back();
  }
  return parts;
}

// Two parts: the normal clustering with two proxies, or halves along the longest axis when
// that does not divide the chart.
std::vector<std::vector<std::uint32_t>> split(const ChartMesh& c) {
  std::vector<int> label;
  try {
    label = detail::segmentByNormals(c.mesh, 2);
  } catch (const Error&) {
    label.clear();
  }
  const bool divides = !label.empty() && std::any_of(label.begin(), label.end(), [&](int l) { return l != label[0]; });
  if (!divides) {
    const mesh::Bounds b = mesh::bounds(c.mesh);
    const glm::dvec3 size = b.size();
    const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
    std::vector<std::pair<double, std::uint32_t>> order;
    for (std::uint32_t i = 0; i < c.mesh.triangles.size(); ++i) {
      const glm::uvec3 t = c.mesh.triangles[i];
      order.emplace_back(c.mesh.positions[t.x][axis] + c.mesh.positions[t.y][axis] + c.mesh.positions[t.z][axis], i);
    }
    std::sort(order.begin(), order.end());
    label.assign(order.size(), 0);
    for (std::size_t k = order.size() / 2; k < order.size(); ++k) label[order[k].second] = 1;
  }
  // Clean the cut: a face with two or three neighbours on the other side changes sides
  // (the clustering leaves saw-tooth borders that pack badly and make long seams).
  const int first = label[0];
  for (int& l : label) l = l == first ? 0 : 1;
  std::unordered_map<std::uint64_t, std::uint32_t> edgeFace;
  std::vector<std::array<int, 3>> across(label.size(), {-1, -1, -1});
  for (std::uint32_t i = 0; i < c.mesh.triangles.size(); ++i) {
    const glm::uvec3 t = c.mesh.triangles[i];
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] = edgeFace.emplace(edgeKey(t[k], t[(k + 1) % 3]), i);
      if (inserted) continue;
      across[i][k] = static_cast<int>(it->second);
      const glm::uvec3 u = c.mesh.triangles[it->second];
      for (int j = 0; j < 3; ++j)
        if (edgeKey(u[j], u[(j + 1) % 3]) == it->first) across[it->second][j] = static_cast<int>(i);
    }
  }
  for (int pass = 0; pass < 4; ++pass) {
    bool changed = false;
    std::array<std::size_t, 2> count{0, 0};
    for (int l : label) ++count[l];
    for (std::size_t i = 0; i < label.size(); ++i) {
      int other = 0;
      for (int n : across[i]) other += n >= 0 && label[n] != label[i];
      if (other >= 2 && count[label[i]] > 1) {
        --count[label[i]];
        label[i] = 1 - label[i];
        ++count[label[i]];
        changed = true;
      }
    }
    if (!changed) break;
  }
  std::vector<std::vector<std::uint32_t>> parts(2);
  for (std::size_t i = 0; i < label.size(); ++i) parts[label[i]].push_back(c.faces[i]);
  return parts;
}

// Charts this small are never split for their shape, only for stretch.
constexpr std::size_t kSmallChart = 16;

struct Chart {
  ChartMesh mesh;
  Flattened map;
};

// Splitting in two at a time leaves more charts than needed: a neighbour often flattens
// well together with a piece cut off it. Greedy merging, smallest chart first, into the
// neighbour it shares most edges with whose union is still a disc within the stretch
// limit; passes repeat until nothing merges. A pair that failed is not tried again until
// one of the two has grown.
void mergeCharts(const mesh::Mesh& m, std::vector<Chart>& charts, double limit, double minFill) {
  std::vector<int> chartOf(m.triangles.size());
  std::vector<int> version(charts.size(), 0);
  std::map<std::pair<int, int>, std::pair<int, int>> failed;  // pair -> versions when it failed
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t c = 0; c < charts.size(); ++c)
      for (std::uint32_t f : charts[c].mesh.faces) chartOf[f] = static_cast<int>(c);
    // Shared edges per neighbouring pair.
    std::unordered_map<std::uint64_t, std::uint32_t> edgeFace;
    edgeFace.reserve(3 * m.triangles.size());
    std::map<std::pair<int, int>, int> shared;
    for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
      const glm::uvec3 t = m.triangles[f];
      for (int k = 0; k < 3; ++k) {
        const auto [it, inserted] = edgeFace.emplace(edgeKey(t[k], t[(k + 1) % 3]), f);
        if (inserted) continue;
        const int a = chartOf[it->second], b = chartOf[f];
        if (a != b) ++shared[{std::min(a, b), std::max(a, b)}];
      }
    }
    std::vector<std::vector<std::pair<int, int>>> neighbours(charts.size());  // (shared edges, chart)
    for (const auto& [pair, n] : shared) {
      neighbours[pair.first].emplace_back(n, pair.second);
      neighbours[pair.second].emplace_back(n, pair.first);
    }
    std::vector<double> area(charts.size());
    for (std::size_t c = 0; c < charts.size(); ++c) area[c] = surfaceArea(charts[c].mesh.mesh);
    std::vector<std::size_t> order(charts.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return area[a] < area[b]; });
    std::vector<bool> touched(charts.size(), false), gone(charts.size(), false);
    for (std::size_t a : order) {
      if (touched[a]) continue;
      auto& list = neighbours[a];
      std::stable_sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      // Of the neighbours it can merge with, the one whose union packs best (all tried at
      // once, on every core).
      std::vector<std::size_t> candidates;
      for (const auto& [n, bi] : list) {
        const auto b = static_cast<std::size_t>(bi);
        if (touched[b]) continue;
        const std::pair<int, int> key(static_cast<int>(std::min(a, b)), static_cast<int>(std::max(a, b)));
        const auto seen = failed.find(key);
        if (seen != failed.end() && seen->second == std::pair(version[key.first], version[key.second])) continue;
        candidates.push_back(b);
      }
      std::vector<std::optional<Chart>> unions(candidates.size());
      std::vector<double> fills(candidates.size(), -1.0);
      parallelFor(static_cast<int>(candidates.size()), resolveThreads(0), [&](int k) {
        std::vector<std::uint32_t> faces = charts[candidates[k]].mesh.faces;
        faces.insert(faces.end(), charts[a].mesh.faces.begin(), charts[a].mesh.faces.end());
        ChartMesh u = extract(m, faces);
        if (u.components != 1 || !isDisc(u.mesh)) return;
        Flattened f = flatten(u.mesh, limit);
        const double fill = f.ok ? boxFill(u.mesh, f.uv) : 0.0;
        if (f.ok && f.distortion.l2_stretch <= limit && (u.faces.size() <= kSmallChart || fill >= minFill)) {
          fills[k] = fill;
          unions[k] = Chart{std::move(u), std::move(f)};
        }
      });
      std::size_t into = charts.size();
      double bestFill = -1.0;
      Chart bestUnion;
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        const std::size_t b = candidates[k];
        if (!unions[k]) {
          const std::pair<int, int> key(static_cast<int>(std::min(a, b)), static_cast<int>(std::max(a, b)));
          failed[key] = {version[key.first], version[key.second]};
        } else if (fills[k] > bestFill) {
          bestFill = fills[k];
          into = b;
          bestUnion = std::move(*unions[k]);
        }
      }
      if (into < charts.size()) {
        charts[into] = std::move(bestUnion);
        ++version[into];
        touched[a] = touched[into] = true;
        gone[a] = true;
        merged = true;
      }
    }
    if (!merged) break;
    // Drop the merged-away charts; versions and failures follow the new numbering.
    std::vector<int> renumber(charts.size(), -1);
    std::vector<Chart> kept;
    std::vector<int> keptVersion;
    for (std::size_t c = 0; c < charts.size(); ++c) {
      if (gone[c]) continue;
      renumber[c] = static_cast<int>(kept.size());
      kept.push_back(std::move(charts[c]));
      keptVersion.push_back(version[c]);
    }
    std::map<std::pair<int, int>, std::pair<int, int>> keptFailed;
    for (const auto& [pair, versions] : failed) {
      const int a = renumber[pair.first], b = renumber[pair.second];
      if (a >= 0 && b >= 0) keptFailed[{a, b}] = versions;
    }
    charts = std::move(kept);
    version = std::move(keptVersion);
    failed = std::move(keptFailed);
  }
}

// ---- Packing --------------------------------------------------------------------------

struct Cells {
  int width = 0, height = 0;
  std::vector<std::uint8_t> on;
  bool at(int x, int y) const { return on[static_cast<std::size_t>(y) * width + x] != 0; }
};

// Conservative cover: every cell of size `cell` (origin at 0) that a triangle touches.
Cells rasterize(const std::vector<glm::dvec2>& uv, const std::vector<glm::uvec3>& tris, glm::dvec2 size, double cell) {
  Cells c;
  c.width = static_cast<int>(std::floor(size.x / cell)) + 1;
  c.height = static_cast<int>(std::floor(size.y / cell)) + 1;
  c.on.assign(static_cast<std::size_t>(c.width) * c.height, 0);
  for (const glm::uvec3& t : tris) {
    const glm::dvec2 p[3] = {uv[t.x] / cell, uv[t.y] / cell, uv[t.z] / cell};
    const glm::dvec2 lo = glm::min(p[0], glm::min(p[1], p[2])), hi = glm::max(p[0], glm::max(p[1], p[2]));
    const int x0 = std::clamp(static_cast<int>(std::floor(lo.x)), 0, c.width - 1);
    const int x1 = std::clamp(static_cast<int>(std::floor(hi.x)), 0, c.width - 1);
    const int y0 = std::clamp(static_cast<int>(std::floor(lo.y)), 0, c.height - 1);
    const int y1 = std::clamp(static_cast<int>(std::floor(hi.y)), 0, c.height - 1);
    const double orientation = cross2(p[1] - p[0], p[2] - p[0]) >= 0 ? 1.0 : -1.0;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        // Separating axis: the cell lies wholly outside one of the triangle's edges.
        bool outside = false;
        for (int k = 0; k < 3 && !outside; ++k) {
          const glm::dvec2 a = p[k], e = p[(k + 1) % 3] - a;
          double most = -1e300;
          for (const glm::dvec2 corner :
               {glm::dvec2(x, y), glm::dvec2(x + 1, y), glm::dvec2(x, y + 1), glm::dvec2(x + 1, y + 1)}) {
            most = std::max(most, orientation * cross2(e, corner - a));
          }
          outside = most < 0.0;
        }
        if (!outside) c.on[static_cast<std::size_t>(y) * c.width + x] = 1;
      }
  }
  return c;
}

// Chebyshev dilation by r cells; the result is offset by r on each side.
Cells dilate(const Cells& c, int r) {
  Cells d;
  d.width = c.width + 2 * r;
  d.height = c.height + 2 * r;
  d.on.assign(static_cast<std::size_t>(d.width) * d.height, 0);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      if (!c.at(x, y)) continue;
      for (int dy = 0; dy <= 2 * r; ++dy)
        std::fill_n(&d.on[static_cast<std::size_t>(y + dy) * d.width + x], 2 * r + 1, std::uint8_t{1});
    }
  return d;
}

// The angle that puts the convex hull in its least-area bounding rectangle.
double boxAngle(const std::vector<glm::dvec2>& uv) {
  std::vector<glm::dvec2> p = uv;
  std::sort(p.begin(), p.end(), [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  std::vector<glm::dvec2> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // Andrew's monotone chain
    while (k >= 2 && cross2(hull[k - 1] - hull[k - 2], p[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 1] - hull[k - 2], p[i] - hull[k - 2]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  double bestArea = 1e300, bestAngle = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 e = hull[(i + 1) % hull.size()] - hull[i];
    if (glm::length(e) == 0.0) continue;
    const double angle = std::atan2(e.y, e.x);
    const glm::dvec2 u(std::cos(angle), std::sin(angle)), v(-u.y, u.x);
    glm::dvec2 lo(1e300), hi(-1e300);
    for (const glm::dvec2& q : hull) {
      const glm::dvec2 r(glm::dot(q, u), glm::dot(q, v));
      lo = glm::min(lo, r);
      hi = glm::max(hi, r);
    }
    const double area = (hi.x - lo.x) * (hi.y - lo.y);
    if (area < bestArea) {
      bestArea = area;
      bestAngle = angle;
    }
  }
  return bestAngle;
}

// Rotated by -angle and moved to the positive quadrant; returns the extent.
glm::dvec2 orient(std::vector<glm::dvec2>& uv, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  glm::dvec2 lo(1e300);
  for (glm::dvec2& p : uv) {
    p = {c * p.x + s * p.y, -s * p.x + c * p.y};
    lo = glm::min(lo, p);
  }
  glm::dvec2 hi(0.0);
  for (glm::dvec2& p : uv) {
    p -= lo;
    hi = glm::max(hi, p);
  }
  return hi;
}

struct Packed {
  double width = 0.0, height = 0.0;
};

// Charts in decreasing `keys`, each in the orientation and place (of eight turns by 45°,
// and every free cell) that keeps the atlas rectangle smallest (or, `square`, its longer
// side shortest), lowest and leftmost on ties; covers
// are dilated by `pad` cells so no two charts come closer than that. Small charts fall into
// the gaps the large ones leave. Moves each chart's UVs into place.
Packed pack(std::vector<std::vector<glm::dvec2>>& uvs, const std::vector<std::vector<glm::uvec3>>& tris,
            const std::vector<double>& keys, double cell, int pad, bool square) {
  std::vector<std::size_t> order(uvs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] > keys[b]; });
  // The grid grows on demand; `used` is the atlas rectangle so far, in cells.
  int gridWidth = 64, gridHeight = 64, usedWidth = 0, usedHeight = 0;
  std::vector<std::uint8_t> grid(static_cast<std::size_t>(gridWidth) * gridHeight, 0);
  auto grow = [&](int w, int h) {
    if (w <= gridWidth && h <= gridHeight) return;
    const int nw = std::max(w, 2 * gridWidth), nh = std::max(h, 2 * gridHeight);
    std::vector<std::uint8_t> bigger(static_cast<std::size_t>(nw) * nh, 0);
    for (int y = 0; y < gridHeight; ++y)
      std::copy_n(&grid[static_cast<std::size_t>(y) * gridWidth], gridWidth, &bigger[static_cast<std::size_t>(y) * nw]);
    grid = std::move(bigger);
    gridWidth = nw;
    gridHeight = nh;
  };
  for (std::size_t ci : order) {
    struct Best {
      std::vector<glm::dvec2> uv;
      Cells cover;
      int x = 0, y = 0;
      double cost = std::numeric_limits<double>::infinity();
      std::pair<int, int> rank{0, 0};
    } best;
    constexpr int turns = 8;
    for (int turn = 0; turn < turns; ++turn) {
      std::vector<glm::dvec2> uv = uvs[ci];
      const double c = std::cos(turn * 2 * M_PI / turns), s = std::sin(turn * 2 * M_PI / turns);
      for (glm::dvec2& p : uv) p = {c * p.x - s * p.y, s * p.x + c * p.y};
      const glm::dvec2 extent = orient(uv, 0.0);
      Cells cover = rasterize(uv, tris[ci], extent, cell);
      const Cells padded = dilate(cover, pad);
      std::vector<std::pair<int, int>> cells;
      for (int y = 0; y < padded.height; ++y)
        for (int x = 0; x < padded.width; ++x)
          if (padded.at(x, y)) cells.emplace_back(x - pad, y - pad);
      // Cells far apart first: a collision is found after a few tests.
      const std::size_t stride = std::max<std::size_t>(1, cells.size() / 16);
      std::vector<std::pair<int, int>> spread;
      spread.reserve(cells.size());
      for (std::size_t s0 = 0; s0 < stride; ++s0)
        for (std::size_t k = s0; k < cells.size(); k += stride) spread.push_back(cells[k]);
      // Up to a padding past the used rectangle: there the dilated cover clears every chart.
      grow(usedWidth + 2 * pad + cover.width + 1, usedHeight + 2 * pad + cover.height + 1);
      for (int y = 0; y <= usedHeight + pad; ++y) {
        for (int x = 0; x <= usedWidth + pad; ++x) {
          const int w = std::max(usedWidth, x + cover.width), h = std::max(usedHeight, y + cover.height);
          // Rectangle area, with a square preferred among equals (textures are square).
          const double cost =
              square ? static_cast<double>(std::max(w, h)) * std::max(w, h) * 1e6 + static_cast<double>(w) * h
                     : static_cast<double>(w) * h * (1.0 + 0.05 * std::max(w, h) / std::min(w, h));
          const std::pair<int, int> rank(y + cover.height, x);
          if (cost > best.cost || (cost == best.cost && rank >= best.rank)) continue;
          bool fits = true;
          for (const auto& [dx, dy] : spread) {
            const int gx = x + dx, gy = y + dy;
            if (gx < 0 || gy < 0) continue;
            if (grid[static_cast<std::size_t>(gy) * gridWidth + gx]) {
              fits = false;
              break;
            }
          }
          if (!fits) continue;
          best.cost = cost;
          best.rank = rank;
          best.x = x;
          best.y = y;
          best.uv = uv;
          best.cover = cover;
        }
      }
    }
    SHANSHUI_CHECK(std::isfinite(best.cost));  // a padding past the used rectangle is always free
    const Cells& cover = best.cover;
    for (int y = 0; y < cover.height; ++y)
      for (int x = 0; x < cover.width; ++x)
        if (cover.at(x, y)) grid[static_cast<std::size_t>(best.y + y) * gridWidth + best.x + x] = 1;
    usedWidth = std::max(usedWidth, best.x + cover.width);
    usedHeight = std::max(usedHeight, best.y + cover.height);
    const glm::dvec2 offset(best.x * cell, best.y * cell);
    for (glm::dvec2& p : best.uv) p += offset;
    uvs[ci] = std::move(best.uv);
  }
  glm::dvec2 lo(1e300), hi(-1e300);
  for (const auto& uv : uvs)
    for (const glm::dvec2& p : uv) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  for (auto& uv : uvs)
    for (glm::dvec2& p : uv) p -= lo;
  Packed result;
  result.width = hi.x - lo.x;
  result.height = hi.y - lo.y;
  return result;
}

}  // namespace

mesh::Mesh parameterizeCharts(const mesh::Mesh& m, const ChartOptions& o, AtlasReport* report,
                              const std::string& what) {
  if (!(o.max_chart_stretch >= 1.0) || !std::isfinite(o.max_chart_stretch)) {
    throw makeError("chart stretch limit ", o.max_chart_stretch, "; expected a number >= 1");
  }
  if (!(o.min_fill >= 0.0 && o.min_fill <= 1.0)) throw makeError("chart fill ", o.min_fill, "; expected [0, 1]");
  if (!(o.padding_texels >= 0.0 && o.padding_texels <= 64.0)) {
    throw makeError("atlas padding ", o.padding_texels, " texels; expected [0, 64]");
  }
  if (o.atlas_resolution < 64 || o.atlas_resolution > 16384) {
    throw makeError("atlas resolution ", o.atlas_resolution, " texels; expected [64, 16384]");
  }
  if (m.triangles.empty()) throw makeError(what, ": no triangles to parameterize");
  AtlasReport local;
  AtlasReport& r = report ? *report : local;
  r = {};

  // Charts: every connected component, split until each is a disc that flattens within the
  // stretch limit (a single triangle always does). Pieces are handled a generation at a
  // time, on every core; results are gathered in order, so the atlas does not depend on
  // the thread count.
  std::vector<Chart> charts;
  std::vector<std::vector<std::uint32_t>> wave(1, std::vector<std::uint32_t>(m.triangles.size()));
  std::iota(wave[0].begin(), wave[0].end(), 0u);
  struct Outcome {
    std::optional<Chart> chart;
    std::vector<std::vector<std::uint32_t>> pieces;
    bool split = false;
  };
  while (!wave.empty()) {
    std::vector<Outcome> outcomes(wave.size());
    parallelFor(static_cast<int>(wave.size()), resolveThreads(0), [&](int i) {
      const std::vector<std::uint32_t>& faces = wave[i];
      Outcome& out = outcomes[i];
      ChartMesh c = extract(m, faces);
      if (c.components > 1) {
        out.pieces.resize(c.components);
        for (std::size_t k = 0; k < faces.size(); ++k) out.pieces[c.component_of_face[k]].push_back(faces[k]);
        return;
      }
      if (isDisc(c.mesh) || faces.size() == 1) {
        Flattened f = flatten(c.mesh, o.max_chart_stretch);
        const bool good = f.ok && f.distortion.l2_stretch <= o.max_chart_stretch;
        if (good && faces.size() > kSmallChart && boxFill(c.mesh, f.uv) < o.min_fill) {
          out.pieces = splitAcross(c, f.uv);
          return;
        }
        if (good || faces.size() == 1) {
          if (f.uv.empty()) f.uv.assign(c.mesh.positions.size(), glm::dvec2(0.0));
          out.chart = Chart{std::move(c), std::move(f)};
          return;
        }
        out.split = true;
      }
      out.pieces = split(c);
    });
    std::vector<std::vector<std::uint32_t>> next;
    for (Outcome& out : outcomes) {
      if (out.chart) charts.push_back(std::move(*out.chart));
      r.splits += out.split;
      for (auto& p : out.pieces)
        if (!p.empty()) next.push_back(std::move(p));
    }
    wave = std::move(next);
  }
  const std::size_t beforeMerging = charts.size();
  mergeCharts(m, charts, o.max_chart_stretch, o.min_fill);
  r.merges = static_cast<int>(beforeMerging - charts.size());

  // Pack, each chart turned into its least bounding rectangle first.
  std::vector<std::vector<glm::dvec2>> uvs;
  std::vector<std::vector<glm::uvec3>> tris;
  std::vector<double> areas;
  double totalArea = 0.0;
  for (Chart& c : charts) {
    std::vector<glm::dvec2> uv = c.map.uv;
    orient(uv, boxAngle(uv));
    uvs.push_back(std::move(uv));
    tris.push_back(c.mesh.mesh.triangles);
    areas.push_back(surfaceArea(c.mesh.mesh));
    totalArea += areas.back();
  }
  if (!(totalArea > 0.0)) throw makeError(what, ": the surface has no area");
  // Packing cells of `perCell` texels, at most 256 across the guessed side.
  const int perCell = std::max(1, o.atlas_resolution / 256);
  const int pad = static_cast<int>(std::ceil(o.padding_texels / perCell));
  // The padding is in texels of an atlas `atlas_resolution` texels along its longer side,
  // known only after packing: pack with a guess of that side, and again with the side found
  // while the padding falls short. Greedy packing depends on the order and the goal: eight tries (largest area, longest
  // side, largest box or longest short side first; smallest rectangle or square), the best
  // usage kept.
  std::vector<double> longest(uvs.size()), boxArea(uvs.size()), shortest(uvs.size());
  for (std::size_t c = 0; c < uvs.size(); ++c) {
    glm::dvec2 hi(0.0);
    for (const glm::dvec2& p : uvs[c]) hi = glm::max(hi, p);
    longest[c] = std::max(hi.x, hi.y);
    shortest[c] = std::min(hi.x, hi.y);
    boxArea[c] = hi.x * hi.y;
  }
  const std::vector<double>* orders[] = {&areas, &longest, &boxArea, &shortest};
  constexpr int variants = 8;
  struct Try {
    std::vector<std::vector<glm::dvec2>> placed;
    Packed packed;
    double usage = -1.0, texel = 0.0;
  };
  std::vector<Try> tries(variants);
  parallelFor(variants, resolveThreads(0), [&](int variant) {
    double side = std::sqrt(totalArea / 0.7);
    for (int attempt = 0; attempt < 6; ++attempt) {
      const double texel = side / o.atlas_resolution;
      std::vector<std::vector<glm::dvec2>> trial = uvs;
      const Packed p = pack(trial, tris, *orders[variant / 2], texel * perCell, pad, variant % 2 == 1);
      const double longer = std::max(p.width, p.height);
      if (longer > side * 1.0001 && attempt + 1 < 6) {
        side = longer;
        continue;
      }
      tries[variant] = {std::move(trial), p, totalArea / std::max(p.width * p.height, 1e-300),
                        longer / o.atlas_resolution};
      break;
    }
  });
  std::size_t bestTry = 0;
  for (std::size_t v = 1; v < tries.size(); ++v)
    if (tries[v].usage > tries[bestTry].usage) bestTry = v;
  std::vector<std::vector<glm::dvec2>> placed = std::move(tries[bestTry].placed);
  const Packed packed = tries[bestTry].packed;
  r.texel = tries[bestTry].texel;
  r.width = packed.width;
  r.height = packed.height;
  r.usage = totalArea / std::max(packed.width * packed.height, 1e-300);

  // The atlas mesh: each chart's vertices in turn, triangles in the input's order.
  const std::vector<glm::vec3> normals = m.normals.size() == m.positions.size() ? m.normals : mesh::vertexNormals(m);
  mesh::Mesh out;
  out.triangles.resize(m.triangles.size());
  r.chart_of_face.assign(m.triangles.size(), -1);
  for (std::size_t ci = 0; ci < charts.size(); ++ci) {
    const ChartMesh& c = charts[ci].mesh;
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (std::size_t v = 0; v < c.source_vertex.size(); ++v) {
      out.positions.push_back(m.positions[c.source_vertex[v]]);
      out.normals.push_back(normals[c.source_vertex[v]]);
      out.uvs.emplace_back(placed[ci][v]);
    }
    for (std::size_t i = 0; i < c.faces.size(); ++i) {
      out.triangles[c.faces[i]] = c.mesh.triangles[i] + glm::uvec3(base);
      r.chart_of_face[c.faces[i]] = static_cast<int>(ci);
    }
    ChartReport cr;
    cr.faces = static_cast<int>(c.faces.size());
    cr.area = areas[ci];
    cr.method = charts[ci].map.method;
    cr.distortion = charts[ci].map.distortion;
    r.charts.push_back(std::move(cr));
  }
  return out;
}

}  // namespace shanshui::param
