// Feature edges of a triangle mesh for brush strokes (seed 002, SPEC.md section 11):
// silhouettes, borders and creases, from an edge-face adjacency built once per mesh.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "shanshui/mesh/mesh.h"

namespace shanshui::strokes {

//! Every undirected edge of a mesh with the (one or two) faces on it, built on load.
struct EdgeGraph {
  std::vector<std::array<std::uint32_t, 2>> vertices;  //!< per edge, smaller index first
  std::vector<std::array<std::int32_t, 2>> faces;      //!< per edge; faces[1] = -1 on a border
  std::vector<glm::dvec3> face_normals;                //!< unit (zero for a zero-area face)
  std::vector<double> normal_dot;                      //!< per edge N1·N2 (1 on a border)
  std::size_t non_manifold = 0;                        //!< edges in more than two faces (ignored)
};

EdgeGraph buildEdgeGraph(const mesh::Mesh& mesh);

enum EdgeKind : std::uint8_t {
  kSilhouette = 1,  //!< (V·N1)(V·N2) <= 0: one face towards the eye, one away
  kBorder = 2,      //!< one face only
  kCrease = 4,      //!< N1·N2 < cos(crease angle). Seed 002 prints |N1·N2| > 0.5, which reads
                    //!< inverted: that would mark the flat edges.
};

struct FeatureEdge {
  std::uint32_t edge = 0;
  std::uint8_t kinds = 0;
  //! Borders and creases are found whatever the view; silhouettes need the eye.
};

//! The feature edges seen from `eye` (a position; silhouettes use V = eye - edge midpoint,
//! so a perspective camera is exact). crease_deg in (0, 180): dihedral angles between the
//! faces' normals above it are creases; 180 or more turns creases off.
std::vector<FeatureEdge> featureEdges(const EdgeGraph& graph, const mesh::Mesh& mesh, glm::dvec3 eye,
                                      double crease_deg);

}  // namespace shanshui::strokes
