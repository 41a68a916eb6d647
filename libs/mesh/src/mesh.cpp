#include "shanshui/mesh/mesh.h"

#include <cmath>

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

std::vector<glm::vec3> vertexNormals(const Mesh& m) {
  std::vector<glm::dvec3> sum(m.positions.size(), glm::dvec3(0.0));
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 n =
        glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]);
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
