// Cutting a closed genus-0 mesh open along one seam so it can be flattened.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "shanshui/mesh/mesh.h"

namespace shanshui::param {

struct SeamCut {
  mesh::Mesh mesh;                  //!< the cut mesh: a topological disc
  std::vector<std::uint32_t> seam;  //!< vertex indices along the seam in the input mesh
  int duplicated = 0;               //!< vertices added (the seam's interior vertices)
};

//! Cuts a closed, consistently oriented, connected triangle mesh of genus 0 along the
//! shortest edge path between two far-apart vertices (the extremes along the longest
//! bounding-box axis). Seam vertices other than the two ends are duplicated; the faces on
//! one side of the seam use the copies. Throws Error for a mesh that is not closed and of
//! genus 0 (`what` names it).
SeamCut cutOpen(const mesh::Mesh& mesh, const std::string& what = "mesh");

}  // namespace shanshui::param
