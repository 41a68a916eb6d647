// CGAL's free-border parameterizers (one translation unit: ~1 min and ~2 GB to compile).
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include "cgal_methods.h"
#include "cgal_surface_mesh.h"

namespace shanshui::param::detail {

std::vector<glm::dvec2> freeBorderUvs(const mesh::Mesh& m, Method method) {
  namespace SMP = CGAL::Surface_mesh_parameterization;
  SurfaceMesh sm = toSurfaceMesh(m);
  const HalfedgeIndex bhd = longestBorder(sm);
  UvMap uv = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
  SMP::Error_code status = SMP::ERROR_WRONG_PARAMETER;
  if (method == Method::Lscm) {
    status = SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), bhd, uv);
  } else if (method == Method::Arap) {
    status = SMP::parameterize(sm, SMP::ARAP_parameterizer_3<SurfaceMesh>(), bhd, uv);
  } else {
    throw makeError("method '", methodName(method), "' is not a free-border method");
  }
  if (status != SMP::OK) throw makeError(methodName(method), " failed: ", statusName(status));
  return readUvs(sm, uv);
}

}  // namespace shanshui::param::detail
