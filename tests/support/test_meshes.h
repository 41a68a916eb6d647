// Meshes with known geometry for tests.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "shanshui/mesh/mesh.h"

namespace shanshui::test {

//! A UV sphere of the given radius and centre, outward-facing triangles.
inline mesh::Mesh uvSphere(double radius, int stacks = 48, int slices = 96,
                           glm::dvec3 centre = glm::dvec3(0.0)) {
  mesh::Mesh m;
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
  m.normals = mesh::vertexNormals(m);
  return m;
}

//! A torus around +z with tube radius `small` at distance `big`, nu × nv vertices (u around
//! the axis, v around the tube); `cosV`, when given, receives cos v per vertex (the
//! analytic curvatures depend on it: K = cos v / (small (big + small cos v)),
//! H = (big + 2 small cos v) / (2 small (big + small cos v))).
inline mesh::Mesh torus(double big, double small, int nu, int nv, std::vector<double>* cosV = nullptr) {
  mesh::Mesh m;
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

//! A regular grid of nx × ny vertices with spacing `cell`, z = height(x, y), CCW seen from +z.
template <typename Height>
mesh::Mesh heightGrid(int nx, int ny, double cell, Height height, glm::dvec3 offset = glm::dvec3(0.0)) {
  mesh::Mesh m;
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

}  // namespace shanshui::test
