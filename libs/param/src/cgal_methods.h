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

}  // namespace shanshui::param::detail
