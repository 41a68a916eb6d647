// A triangle mesh uploaded to the GPU (positions and normals as float, relative to a centre).
#pragma once

#include <array>
#include <vector>

#include <epoxy/gl.h>

#include "shanshui/mesh/mesh.h"
#include "shanshui/render/gl_resources.h"

namespace shanshui::render {

class GpuMesh {
 public:
  GpuMesh() = default;
  //! Positions are uploaded relative to `centre` (subtracted in double first), so meshes
  //! in UTM metres keep their precision. Normals are computed when the mesh has none.
  //! UVs, when the mesh has them, go to attribute 2; a per-vertex scalar (curvature), when
  //! given, to attribute 3.
  GpuMesh(const mesh::Mesh& m, const glm::dvec3& centre, const std::vector<float>* scalar = nullptr,
          bool sorted_orders = false);

  //! Attribute 0: position (vec3), 1: normal (vec3).
  void draw() const;

  //! Draws the triangles roughly front to back for a camera looking along `view_dir`
  //! (model space), so early depth tests reject hidden fragments before they are shaded:
  //! six orders of chunks of the mesh's own order, by the chunks' position along ±x, ±y,
  //! ±z, are kept and the one closest to the view direction is used (chunks, not single
  //! triangles, keep shared vertices near in the order). Needs the mesh built with
  //! sorted_orders.
  void drawFrontToBack(const glm::vec3& view_dir) const;
  std::size_t triangleCount() const { return static_cast<std::size_t>(indexCount_ / 3); }

 private:
  VertexArray vao_;
  std::array<Buffer, 5> buffers_;  //!< positions, normals, indices, UVs, scalars
  GLsizei indexCount_ = 0;
  bool sorted_ = false;  //!< the element buffer holds the six sorted orders after the original
};

}  // namespace shanshui::render
