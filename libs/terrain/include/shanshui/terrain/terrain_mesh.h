// Heightfield to triangle mesh.
#pragma once

#include "shanshui/mesh/mesh.h"
#include "shanshui/terrain/heightfield.h"

namespace shanshui::terrain {

struct TerrainMeshOptions {
  double z_scale = 1.0;          //!< vertical exaggeration, (0, 1000]
  int step = 1;                  //!< keep every step-th sample in both directions, [1, 4096]
  std::size_t max_vertices = 0;  //!< if > 0, raise step until the grid has at most this many
};

struct TerrainMeshInfo {
  int step = 1;                   //!< the step actually used
  glm::dvec3 offset{0.0};         //!< subtracted from x and y (z keeps true elevation)
  std::size_t skipped_cells = 0;  //!< cells with a missing corner (no or one triangle)
};

//! Checks the option ranges; throws Error naming the flag, the value and the range.
void validate(const TerrainMeshOptions& options);

//! A Z-up mesh: x east, y north, z = elevation · z_scale, in metres, recentred in x and y
//! (in double) so large projected coordinates survive conversion to float. Each full cell
//! becomes two counter-clockwise triangles split along the diagonal with the smaller
//! elevation difference; a cell with one missing corner becomes one triangle. Throws
//! Error when no triangle can be made (NODATA-only, or a single row/column).
mesh::Mesh heightfieldToMesh(const Heightfield& field, const TerrainMeshOptions& options,
                             TerrainMeshInfo* info = nullptr, const std::string& name = "terrain");

}  // namespace shanshui::terrain
