#include "shanshui/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace shanshui::mesh {

Bounds bounds(const std::vector<glm::dvec3>& positions) {
  Bounds b;
  if (positions.empty()) return b;
  b.min = b.max = positions.front();
  for (const glm::dvec3& p : positions) {
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

glm::dvec3 recentre(Mesh& m) {
  const glm::dvec3 offset = bounds(m).centre();
  for (glm::dvec3& p : m.positions) p -= offset;
  return offset;
}

namespace {

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

}  // namespace

ManifoldProblems manifoldProblems(const Mesh& m) {
  ManifoldProblems problems;
  // Edges: (low, high, direction) per triangle side, sorted so one edge's uses are adjacent.
  std::vector<std::tuple<std::uint32_t, std::uint32_t, bool>> sides;
  sides.reserve(3 * m.triangles.size());
  for (const glm::uvec3& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      sides.emplace_back(std::min(a, b), std::max(a, b), a < b);
    }
  }
  std::sort(sides.begin(), sides.end());
  for (std::size_t e = 0; e < sides.size();) {
    std::size_t f = e + 1;
    while (f < sides.size() && std::get<0>(sides[f]) == std::get<0>(sides[e]) &&
           std::get<1>(sides[f]) == std::get<1>(sides[e])) {
      ++f;
    }
    if (f - e > 2) ++problems.edges_over_two_faces;
    if (f - e == 2 && std::get<2>(sides[e]) == std::get<2>(sides[e + 1])) ++problems.edges_same_direction;
    e = f;
  }
  // Fans: the corners at a vertex are joined when their triangles share an edge there; a
  // vertex with more than one group of corners is pinched.
  std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> spokes;  // vertex, other end, corner
  spokes.reserve(6 * m.triangles.size());
  for (std::uint32_t t = 0; t < m.triangles.size(); ++t) {
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t v = m.triangles[t][k];
      spokes.emplace_back(v, m.triangles[t][(k + 1) % 3], 3 * t + k);
      spokes.emplace_back(v, m.triangles[t][(k + 2) % 3], 3 * t + k);
    }
  }
  std::sort(spokes.begin(), spokes.end());
  std::vector<std::uint32_t> parent(3 * m.triangles.size());
  std::iota(parent.begin(), parent.end(), 0u);
  for (std::size_t i = 1; i < spokes.size(); ++i) {
    if (std::get<0>(spokes[i]) == std::get<0>(spokes[i - 1]) && std::get<1>(spokes[i]) == std::get<1>(spokes[i - 1])) {
      parent[findRoot(parent, std::get<2>(spokes[i]))] = findRoot(parent, std::get<2>(spokes[i - 1]));
    }
  }
  for (std::size_t i = 0; i < spokes.size();) {
    std::size_t j = i;
    std::vector<std::uint32_t> roots;
    while (j < spokes.size() && std::get<0>(spokes[j]) == std::get<0>(spokes[i])) {
      roots.push_back(findRoot(parent, std::get<2>(spokes[j])));
      ++j;
    }
    std::sort(roots.begin(), roots.end());
    if (std::unique(roots.begin(), roots.end()) - roots.begin() > 1) ++problems.pinched_vertices;
    i = j;
  }
  return problems;
}

std::vector<glm::vec3> vertexNormals(const Mesh& m) {
  std::vector<glm::dvec3> sum(m.positions.size(), glm::dvec3(0.0));
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 n = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    sum[t.x] += n;  // |n| = 2 * area: area weighting for free
    sum[t.y] += n;
    sum[t.z] += n;
  }
  std::vector<glm::vec3> normals(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = glm::length(sum[i]);
    normals[i] = (len > 0.0 && std::isfinite(len)) ? glm::vec3(sum[i] / len) : glm::vec3(0, 0, 1);
  }
  return normals;
}

std::vector<std::uint32_t> splitAtCreases(Mesh& m, double crease_deg) {
  const std::size_t nt = m.triangles.size(), nv = m.positions.size();
  std::vector<std::uint32_t> origin(nv);
  std::iota(origin.begin(), origin.end(), 0u);
  if (nt == 0) return origin;
  // Face normals: unit for the angle test, area-weighted for the sums.
  std::vector<glm::dvec3> area(nt), unit(nt);
  for (std::size_t f = 0; f < nt; ++f) {
    const glm::uvec3 t = m.triangles[f];
    area[f] = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    const double len = glm::length(area[f]);
    unit[f] = len > 0.0 && std::isfinite(len) ? area[f] / len : glm::dvec3(0.0);
  }
  // Corners (3f + k) of one vertex are joined across every edge with two faces whose
  // normals are within the crease angle; each joined set becomes one vertex.
  std::vector<std::uint32_t> parent(3 * nt);
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  struct Half {
    std::uint64_t key;
    std::uint32_t face;
    int k;  // the edge runs from corner k to corner k + 1
  };
  std::vector<Half> half;
  half.reserve(3 * nt);
  for (std::size_t f = 0; f < nt; ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = m.triangles[f][k], b = m.triangles[f][(k + 1) % 3];
      half.push_back(
          {(static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b), static_cast<std::uint32_t>(f), k});
    }
  }
  std::sort(half.begin(), half.end(), [](const Half& x, const Half& y) { return x.key < y.key; });
  const double cosCrease = std::cos(std::clamp(crease_deg, 0.0, 180.0) * M_PI / 180.0);
  auto corner = [&](std::uint32_t f, std::uint32_t v) {
    for (int k = 0; k < 3; ++k)
      if (m.triangles[f][k] == v) return 3 * f + static_cast<std::uint32_t>(k);
    return 3 * f;
  };
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    if (j - i == 2) {  // a manifold edge; an edge of three or more faces stays a crease
      const std::uint32_t f0 = half[i].face, f1 = half[i + 1].face;
      const bool smooth = crease_deg >= 180.0 || glm::dot(unit[f0], unit[f1]) >= cosCrease;
      if (smooth) {
        for (std::uint32_t v :
             {static_cast<std::uint32_t>(half[i].key >> 32), static_cast<std::uint32_t>(half[i].key & 0xffffffffu)}) {
          const std::uint32_t a = find(corner(f0, v)), b = find(corner(f1, v));
          if (a != b) parent[a] = b;
        }
      }
    }
    i = j;
  }
  // One output vertex per (vertex, set): the first set of a vertex keeps its index.
  std::vector<std::int64_t> vertexOfSet(3 * nt, -1);
  std::vector<bool> used(nv, false);
  std::vector<glm::dvec3> sum(nv, glm::dvec3(0.0));
  for (std::size_t f = 0; f < nt; ++f) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t c = 3 * static_cast<std::uint32_t>(f) + static_cast<std::uint32_t>(k);
      const std::uint32_t root = find(c), v = m.triangles[f][k];
      if (vertexOfSet[root] < 0) {
        if (!used[v]) {
          used[v] = true;
          vertexOfSet[root] = v;
        } else {
          vertexOfSet[root] = static_cast<std::int64_t>(m.positions.size());
          m.positions.push_back(m.positions[v]);
          if (m.uvs.size() == nv) m.uvs.push_back(m.uvs[v]);
          origin.push_back(v);
          sum.emplace_back(0.0);
        }
      }
      const auto out = static_cast<std::uint32_t>(vertexOfSet[root]);
      m.triangles[f][k] = out;
      sum[out] += area[f];
    }
  }
  m.normals.resize(m.positions.size());
  for (std::size_t i = 0; i < sum.size(); ++i) {
    const double len = glm::length(sum[i]);
    m.normals[i] = (len > 0.0 && std::isfinite(len)) ? glm::vec3(sum[i] / len) : glm::vec3(0, 0, 1);
  }
  return origin;
}

}  // namespace shanshui::mesh
