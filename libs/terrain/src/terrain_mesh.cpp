#include "shanshui/terrain/terrain_mesh.h"

#include <cmath>

#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"

namespace shanshui::terrain {

void validate(const TerrainMeshOptions& options) {
  if (!(options.z_scale > 0.0 && options.z_scale <= 1000.0)) {
    throw makeError("--z-scale: ", options.z_scale, " is out of range; expected (0, 1000]");
  }
  if (options.step < 1 || options.step > 4096) {
    throw makeError("--step: ", options.step, " is out of range; expected [1, 4096]");
  }
  if (options.max_vertices != 0 && options.max_vertices < 4) {
    throw makeError("--max-vertices: ", options.max_vertices, " is too small; expected 0 (no limit) or >= 4");
  }
}

mesh::Mesh heightfieldToMesh(const Heightfield& field, const TerrainMeshOptions& options, TerrainMeshInfo* info,
                             const std::string& name) {
  validate(options);
  int step = options.step;
  auto gridVertices = [&](int s) {
    return static_cast<std::size_t>((field.columns - 1) / s + 1) * static_cast<std::size_t>((field.rows - 1) / s + 1);
  };
  if (options.max_vertices > 0) {
    while (gridVertices(step) > options.max_vertices && step < std::max(field.columns, field.rows)) ++step;
  }
  const int cols = (field.columns - 1) / step + 1;
  const int rows = (field.rows - 1) / step + 1;
  if (cols < 2 || rows < 2) {
    throw makeError(name, ": grid of ", field.columns, " x ", field.rows, " samples at step ", step,
                    " has fewer than two rows or columns; nothing to triangulate");
  }

  mesh::Mesh m;
  std::vector<std::uint32_t> id(static_cast<std::size_t>(cols) * rows, UINT32_MAX);
  auto z = [&](int c, int r) { return field.at(c * step, r * step); };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double e = z(c, r);
      if (std::isnan(e)) continue;
      if (std::abs(e * options.z_scale) > mesh::kMaxCoordinate) {
        throw makeError(name, ": elevation ", e, " (times --z-scale ", options.z_scale, ") is outside +-",
                        mesh::kMaxCoordinate, "; the mesh readers refuse such coordinates");
      }
      id[static_cast<std::size_t>(r) * cols + c] = static_cast<std::uint32_t>(m.positions.size());
      m.positions.emplace_back(field.origin_x + c * step * field.cell_x, field.origin_y - r * step * field.cell_y,
                               e * options.z_scale);
    }
  }
  std::size_t skipped = 0;
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      const std::uint32_t nw = id[static_cast<std::size_t>(r) * cols + c];
      const std::uint32_t ne = id[static_cast<std::size_t>(r) * cols + c + 1];
      const std::uint32_t sw = id[static_cast<std::size_t>(r + 1) * cols + c];
      const std::uint32_t se = id[static_cast<std::size_t>(r + 1) * cols + c + 1];
      const int missing = (nw == UINT32_MAX) + (ne == UINT32_MAX) + (sw == UINT32_MAX) + (se == UINT32_MAX);
      if (missing == 0) {
        // Split along the diagonal whose ends are closer in height: it follows ridges and
        // valleys instead of cutting across them.
        if (std::abs(z(c, r) - z(c + 1, r + 1)) <= std::abs(z(c + 1, r) - z(c, r + 1))) {
          m.triangles.emplace_back(sw, se, nw);  // diagonal nw-se
          m.triangles.emplace_back(se, ne, nw);
        } else {
          m.triangles.emplace_back(sw, se, ne);  // diagonal sw-ne
          m.triangles.emplace_back(sw, ne, nw);
        }
        continue;
      }
      ++skipped;
      if (missing == 1) {  // the three valid corners, counter-clockwise seen from above
        if (nw == UINT32_MAX)
          m.triangles.emplace_back(sw, se, ne);
        else if (ne == UINT32_MAX)
          m.triangles.emplace_back(sw, se, nw);
        else if (sw == UINT32_MAX)
          m.triangles.emplace_back(se, ne, nw);
        else
          m.triangles.emplace_back(sw, ne, nw);
      }
    }
  }
  if (m.triangles.empty()) {
    throw makeError(name, ": no grid cell has three valid corners; nothing to triangulate");
  }
  // Drop samples no triangle uses (isolated valid points among NODATA).
  std::vector<std::uint32_t> remap(m.positions.size(), UINT32_MAX);
  std::vector<glm::dvec3> used;
  for (glm::uvec3& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (remap[t[k]] == UINT32_MAX) {
        remap[t[k]] = static_cast<std::uint32_t>(used.size());
        used.push_back(m.positions[t[k]]);
      }
      t[k] = remap[t[k]];
    }
  }
  m.positions = std::move(used);

  const mesh::Bounds b = mesh::bounds(m);
  const glm::dvec3 offset(b.centre().x, b.centre().y, 0.0);
  for (glm::dvec3& p : m.positions) p -= offset;
  m.normals = mesh::vertexNormals(m);
  if (info) {
    info->step = step;
    info->offset = offset;
    info->skipped_cells = skipped;
  }
  return m;
}

}  // namespace shanshui::terrain
