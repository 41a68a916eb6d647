#include "shanshui/mesh/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace shanshui::mesh {

Mesh uvSphere(double radius, int stacks, int slices, glm::dvec3 centre) {
  Mesh m;
  const double pi = std::numbers::pi;
  m.positions.push_back(centre + glm::dvec3(0, 0, radius));
  for (int i = 1; i < stacks; ++i) {
    const double theta = pi * i / stacks;
    for (int j = 0; j < slices; ++j) {
      const double phi = 2 * pi * j / slices;
      m.positions.push_back(centre + radius * glm::dvec3(std::sin(theta) * std::cos(phi),
                                                         std::sin(theta) * std::sin(phi), std::cos(theta)));
    }
  }
  m.positions.push_back(centre + glm::dvec3(0, 0, -radius));
  const auto ring = [&](int i, int j) { return 1u + static_cast<unsigned>((i - 1) * slices + (j % slices)); };
  const unsigned south = static_cast<unsigned>(m.positions.size() - 1);
  for (int j = 0; j < slices; ++j) {
    m.triangles.emplace_back(0u, ring(1, j), ring(1, j + 1));
    for (int i = 1; i + 1 < stacks; ++i) {
      m.triangles.emplace_back(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
      m.triangles.emplace_back(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
    m.triangles.emplace_back(ring(stacks - 1, j), south, ring(stacks - 1, j + 1));
  }
  m.normals = vertexNormals(m);
  return m;
}

Mesh torus(double big, double small, int nu, int nv, std::vector<double>* cosV) {
  Mesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu, v = 2 * std::numbers::pi * j / nv;
      m.positions.emplace_back((big + small * std::cos(v)) * std::cos(u), (big + small * std::cos(v)) * std::sin(u),
                               small * std::sin(v));
      if (cosV) cosV->push_back(std::cos(v));
    }
  const auto at = [&](int i, int j) { return static_cast<unsigned>((i % nu) * nv + (j % nv)); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

Mesh icosphere(int levels) {
  Mesh m;
  const double t = (1 + std::sqrt(5.0)) / 2;
  m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  m.triangles = {{0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : m.positions) p = glm::normalize(p);
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<unsigned, unsigned>, unsigned> midpoints;
    auto midpoint = [&](unsigned a, unsigned b) {
      const auto key = std::minmax(a, b);
      const auto [it, fresh] = midpoints.try_emplace(key, static_cast<unsigned>(m.positions.size()));
      if (fresh) m.positions.push_back(glm::normalize(m.positions[a] + m.positions[b]));
      return it->second;
    };
    std::vector<glm::uvec3> next;
    next.reserve(m.triangles.size() * 4);
    for (const glm::uvec3& f : m.triangles) {
      const unsigned ab = midpoint(f.x, f.y), bc = midpoint(f.y, f.z), ca = midpoint(f.z, f.x);
      next.insert(next.end(), {{f.x, ab, ca}, {ab, f.y, bc}, {ca, bc, f.z}, {ab, bc, ca}});
    }
    m.triangles = std::move(next);
  }
  return m;
}

Mesh unitCube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const unsigned sides[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : sides) {
    m.triangles.emplace_back(q[0], q[1], q[2]);
    m.triangles.emplace_back(q[0], q[2], q[3]);
  }
  return m;
}

}  // namespace shanshui::mesh
