// Triangle meshes and polygon soups: the geometry types shared by shanshui's libraries.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace shanshui::mesh {

//! What a file holds before repair: polygons of any size, indices not yet validated.
//! Attributes are per vertex: empty, or one entry per position.
struct PolygonSoup {
  std::vector<glm::dvec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::vector<std::uint32_t>> faces;
  std::vector<std::string> notes;  //!< conversions the reader applied (units, axes)
};

//! An indexed triangle mesh. Positions are double so that UTM-sized coordinates survive
//! until recentre(); normals and uvs are empty or one per vertex.
struct Mesh {
  std::vector<glm::dvec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::uvec3> triangles;

  std::size_t vertexCount() const { return positions.size(); }
  std::size_t triangleCount() const { return triangles.size(); }
};

struct Bounds {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
  glm::dvec3 centre() const { return 0.5 * (min + max); }
  glm::dvec3 size() const { return max - min; }
  //! Corner i of 8: bit 0 picks max.x, bit 1 max.y, bit 2 max.z.
  glm::dvec3 corner(int i) const { return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z}; }
};

//! Axis-aligned bounds of the positions (all zero for an empty mesh).
Bounds bounds(const std::vector<glm::dvec3>& positions);
inline Bounds bounds(const Mesh& m) {
  return bounds(m.positions);
}

//! Moves the mesh so that its bounding-box centre is at the origin; returns the offset
//! that was subtracted (add it back to get the original coordinates). Done in double.
glm::dvec3 recentre(Mesh& m);

//! What keeps a triangle mesh from being an oriented 2-manifold (with border), counted on
//! its indices: edges shared by more than two triangles, edges two triangles traverse in
//! the same direction (orientations disagree), and vertices whose triangles form more than
//! one fan (two surfaces touching at a point).
struct ManifoldProblems {
  std::size_t edges_over_two_faces = 0;
  std::size_t edges_same_direction = 0;
  std::size_t pinched_vertices = 0;
  bool any() const { return edges_over_two_faces + edges_same_direction + pinched_vertices > 0; }
};
ManifoldProblems manifoldProblems(const Mesh& m);

//! Area-weighted per-vertex normals (unit length; +Z for a vertex whose faces have no area).
std::vector<glm::vec3> vertexNormals(const Mesh& m);

//! Normals as a modelling tool makes them: smooth across edges whose two faces meet at
//! less than `crease_deg` degrees, split across sharper edges (and edges of three or more
//! faces), so a cube shows six flat faces. Vertices on a crease are duplicated (positions
//! and UVs copied); `m.normals` is rewritten, area-weighted within each smooth fan. 180:
//! smooth everywhere, nothing split. Returns, for every vertex of the result, the vertex
//! it was copied from, so that per-vertex data can follow.
std::vector<std::uint32_t> splitAtCreases(Mesh& m, double crease_deg);

}  // namespace shanshui::mesh
