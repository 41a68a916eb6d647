// CGAL's variational shape approximation, used only for its face partition (one more
// CGAL translation unit, built in parallel with the parameterizers).
#include <CGAL/Surface_mesh_approximation/approximate_triangle_mesh.h>

#include "cgal_methods.h"
#include "cgal_surface_mesh.h"

namespace shanshui::param::detail {

std::vector<int> segmentByNormals(const mesh::Mesh& m, int proxies) {
  namespace VSA = CGAL::Surface_mesh_approximation;
  SurfaceMesh sm = toSurfaceMesh(m);
  auto proxy = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:proxy", 0).first;
  const auto faces = static_cast<int>(sm.number_of_faces());
  // Hierarchical seeding is deterministic (it adds proxies where the error is largest);
  // the random one would call std::rand.
  VSA::approximate_triangle_mesh(sm, CGAL::parameters::seeding_method(VSA::HIERARCHICAL)
                                         .max_number_of_proxies(static_cast<std::size_t>(std::clamp(proxies, 1, faces)))
                                         .number_of_iterations(20)
                                         .face_proxy_map(proxy));
  std::vector<int> out(sm.number_of_faces());
  for (auto f : sm.faces()) out[f.idx()] = static_cast<int>(proxy[f]);
  return out;
}

}  // namespace shanshui::param::detail
