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

}  // namespace shanshui::mesh
