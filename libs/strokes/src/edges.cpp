#include "shanshui/strokes/edges.h"

#include <algorithm>
#include <cmath>

#include "shanshui/core/error.h"

namespace shanshui::strokes {

EdgeGraph buildEdgeGraph(const mesh::Mesh& m) {
  EdgeGraph g;
  // Sorted (edge key, face) pairs: each run of equal keys is one edge.
  std::vector<std::pair<std::uint64_t, std::int32_t>> half;
  half.reserve(3 * m.triangles.size());
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const glm::uvec3 t = m.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      half.emplace_back((static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b),
                        static_cast<std::int32_t>(f));
    }
  }
  std::sort(half.begin(), half.end());
  g.face_normals.resize(m.triangles.size());
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const glm::uvec3 t = m.triangles[f];
    const glm::dvec3 n = glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
    const double length = glm::length(n);
    g.face_normals[f] = length > 0.0 ? n / length : glm::dvec3(0.0);
  }
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].first == half[i].first) ++j;
    if (j - i > 2) {
      ++g.non_manifold;
    } else {
      const std::int32_t f0 = half[i].second, f1 = j - i == 2 ? half[i + 1].second : -1;
      g.vertices.push_back(
          {static_cast<std::uint32_t>(half[i].first >> 32), static_cast<std::uint32_t>(half[i].first & 0xffffffffu)});
      g.faces.push_back({f0, f1});
      g.normal_dot.push_back(f1 < 0 ? 1.0 : glm::dot(g.face_normals[f0], g.face_normals[f1]));
    }
    i = j;
  }
  return g;
}

std::vector<FeatureEdge> featureEdges(const EdgeGraph& g, const mesh::Mesh& m, glm::dvec3 eye, double creaseDeg) {
  if (!(creaseDeg > 0.0)) throw makeError("crease angle ", creaseDeg, " degrees; expected (0, 180]");
  const double creaseCos = creaseDeg >= 180.0 ? -2.0 : std::cos(creaseDeg * M_PI / 180.0);
  std::vector<FeatureEdge> out;
  for (std::size_t e = 0; e < g.vertices.size(); ++e) {
    const auto [f0, f1] = g.faces[e];
    std::uint8_t kinds = 0;
    if (f1 < 0) {
      kinds |= kBorder;
    } else {
      const glm::dvec3 mid = 0.5 * (m.positions[g.vertices[e][0]] + m.positions[g.vertices[e][1]]);
      const glm::dvec3 v = eye - mid;
      const bool flat = g.face_normals[f0] == glm::dvec3(0.0) || g.face_normals[f1] == glm::dvec3(0.0);
      if (!flat && glm::dot(v, g.face_normals[f0]) * glm::dot(v, g.face_normals[f1]) <= 0.0) kinds |= kSilhouette;
      if (g.normal_dot[e] < creaseCos) kinds |= kCrease;
    }
    if (kinds) out.push_back({static_cast<std::uint32_t>(e), kinds});
  }
  return out;
}

}  // namespace shanshui::strokes
