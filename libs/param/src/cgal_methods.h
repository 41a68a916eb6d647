// Internal: the CGAL parameterizers behind a CGAL-free interface. Each function takes a
// clean disc-topology triangle mesh (positions recentred) and returns one UV per vertex,
// or throws Error with CGAL's status named.
#pragma once

#include <vector>

#include "shanshui/mesh/mesh.h"
#include "shanshui/param/parameterize.h"

namespace shanshui::param::detail {

//! mvc, dcm, tutte, authalic on a circle or square border (cgal_fixed_border.cpp).
std::vector<glm::dvec2> fixedBorderUvs(const mesh::Mesh& mesh, Method method, Border border, int authalicIterations);

//! lscm, arap with CGAL's default two-vertex border (cgal_free_border.cpp).
std::vector<glm::dvec2> freeBorderUvs(const mesh::Mesh& mesh, Method method);

//! Face labels 0..k-1 of a variational shape approximation with k plane proxies (L2,1
//! metric: faces grouped by normal, each region connected) (cgal_segment.cpp). Any
//! manifold triangle mesh; k is clamped to [components, faces].
std::vector<int> segmentByNormals(const mesh::Mesh& mesh, int proxies);

}  // namespace shanshui::param::detail
