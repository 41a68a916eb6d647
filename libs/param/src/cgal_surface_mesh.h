// Internal, included only by the CGAL translation units: conversion to CGAL::Surface_mesh
// and the status names (CGAL 5.5's own message table is off by one, SPEC.md section 5).
#pragma once

#include <vector>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>

#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh.h"

namespace shanshui::param::detail {

using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;
using UvMap = SurfaceMesh::Property_map<VertexIndex, Kernel::Point_2>;

inline const char* statusName(CGAL::Surface_mesh_parameterization::Error_code code) {
  namespace SMP = CGAL::Surface_mesh_parameterization;
  switch (code) {
    case SMP::OK:
      return "ok";
    case SMP::ERROR_EMPTY_MESH:
      return "empty mesh";
    case SMP::ERROR_NON_TRIANGULAR_MESH:
      return "not a triangle mesh";
    case SMP::ERROR_NO_TOPOLOGICAL_DISC:
      return "not a topological disc";
    case SMP::ERROR_NO_TOPOLOGICAL_BALL:
      return "not a topological ball";
    case SMP::ERROR_BORDER_TOO_SHORT:
      return "border too short";
    case SMP::ERROR_NON_CONVEX_BORDER:
      return "border not convex";
    case SMP::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM:
      return "cannot solve the linear system";
    case SMP::ERROR_NO_1_TO_1_MAPPING:
      return "no one-to-one mapping";
    case SMP::ERROR_WRONG_PARAMETER:
      return "wrong parameter";
  }
  return "unknown status";
}

//! Vertex i of `mesh` becomes vertex i of the surface mesh.
inline SurfaceMesh toSurfaceMesh(const mesh::Mesh& m) {
  SurfaceMesh sm;
  sm.reserve(m.positions.size(), 3 * m.triangles.size() / 2 + 8, m.triangles.size());
  for (const glm::dvec3& p : m.positions) sm.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
  for (const glm::uvec3& t : m.triangles) {
    if (sm.add_face(VertexIndex(t.x), VertexIndex(t.y), VertexIndex(t.z)) == SurfaceMesh::null_face()) {
      throw makeError("mesh is not manifold at triangle (", t.x, ", ", t.y, ", ", t.z, "); repair it first");
    }
  }
  return sm;
}

inline HalfedgeIndex longestBorder(const SurfaceMesh& sm) {
  const HalfedgeIndex h = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  if (h == SurfaceMesh::null_halfedge()) throw makeError("mesh has no border (closed); cut it open first");
  return h;
}

inline std::vector<glm::dvec2> readUvs(const SurfaceMesh& sm, const UvMap& uv) {
  std::vector<glm::dvec2> out(sm.number_of_vertices());
  for (VertexIndex v : sm.vertices()) out[v.idx()] = {uv[v].x(), uv[v].y()};
  return out;
}

}  // namespace shanshui::param::detail
