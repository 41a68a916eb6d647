// Meshes with known geometry: the analytic surfaces the tests and benchmarks measure
// against (curvature, normals, distortion), and the canvas pass's dome.
#pragma once

#include <vector>

#include "shanshui/mesh/mesh.h"

namespace shanshui::mesh {

//! A UV sphere of the given radius and centre, outward-facing triangles.
Mesh uvSphere(double radius, int stacks = 48, int slices = 96, glm::dvec3 centre = glm::dvec3(0.0));

//! A torus around +z with tube radius `small` at distance `big`, nu × nv vertices (u around
//! the axis, v around the tube); `cosV`, when given, receives cos v per vertex (the
//! analytic curvatures depend on it: K = cos v / (small (big + small cos v)),
//! H = (big + 2 small cos v) / (2 small (big + small cos v))).
Mesh torus(double big, double small, int nu, int nv, std::vector<double>* cosV = nullptr);

//! The unit cube [0,1]³, two outward triangles per side (18 edges: 12 creases, 6 flat
//! diagonals).
Mesh unitCube();

//! A sphere of radius 1 around the origin: an icosahedron with each face split into 4,
//! `levels` times (20 · 4^levels triangles).
Mesh icosphere(int levels);

//! A regular grid of nx × ny vertices with spacing `cell`, z = height(x, y), CCW seen from +z.
template <typename Height>
Mesh heightGrid(int nx, int ny, double cell, Height height, glm::dvec3 offset = glm::dvec3(0.0)) {
  Mesh m;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = i * cell, y = j * cell;
      m.positions.push_back(offset + glm::dvec3(x, y, height(x, y)));
    }
  const auto at = [&](int i, int j) { return static_cast<unsigned>(j * nx + i); };
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

}  // namespace shanshui::mesh
