// Independent checks of mesh validity (no CGAL): the oracle the repair tests use.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "shanshui/mesh/mesh.h"

namespace shanshui::test {

struct MeshFacts {
  bool valid_indices = true;
  bool finite = true;
  std::size_t repeated_vertex_faces = 0;  //!< triangles using a vertex twice
  std::size_t zero_area_faces = 0;
  std::size_t non_manifold_edges = 0;  //!< used by more than two faces
  std::size_t inconsistent_edges = 0;  //!< the same directed edge in two faces
  std::size_t boundary_edges = 0;
  double signed_volume = 0.0;  //!< > 0 for an outward closed surface
};

inline MeshFacts meshFacts(const mesh::Mesh& m) {
  MeshFacts f;
  for (const auto& p : m.positions) f.finite &= std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
  std::map<std::pair<unsigned, unsigned>, int> directed, undirected;
  for (const auto& t : m.triangles) {
    if (t.x >= m.positions.size() || t.y >= m.positions.size() || t.z >= m.positions.size()) {
      f.valid_indices = false;
      continue;
    }
    if (t.x == t.y || t.y == t.z || t.x == t.z) ++f.repeated_vertex_faces;
    const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    if (glm::length(glm::cross(b - a, c - a)) == 0.0) ++f.zero_area_faces;
    f.signed_volume += glm::dot(a, glm::cross(b, c)) / 6.0;
    for (int k = 0; k < 3; ++k) {
      const unsigned u = t[k], v = t[(k + 1) % 3];
      ++directed[{u, v}];
      ++undirected[{std::min(u, v), std::max(u, v)}];
    }
  }
  for (const auto& [e, n] : directed) f.inconsistent_edges += n > 1;
  for (const auto& [e, n] : undirected) {
    f.non_manifold_edges += n > 2;
    f.boundary_edges += n == 1;
  }
  return f;
}

//! Everything repair promises about its output.
inline void expectCleanMesh(const mesh::Mesh& m, const std::string& name) {
  SCOPED_TRACE(name);
  const MeshFacts f = meshFacts(m);
  EXPECT_GT(m.triangles.size(), 0u);
  EXPECT_TRUE(f.valid_indices);
  EXPECT_TRUE(f.finite);
  EXPECT_EQ(f.repeated_vertex_faces, 0u);
  EXPECT_EQ(f.zero_area_faces, 0u);
  EXPECT_EQ(f.non_manifold_edges, 0u);
  EXPECT_EQ(f.inconsistent_edges, 0u);
  EXPECT_EQ(m.normals.size(), m.positions.size());
}

}  // namespace shanshui::test
