// Object-space curvature per vertex, for the feature lines of seed 001 Eq. 1 (SPEC.md
// section 6): precomputed on load and passed to the line pass as a vertex attribute.
#pragma once

#include <vector>

#include "shanshui/mesh/mesh.h"

namespace shanshui::mesh {

//! Discrete differential geometry at the vertices (Meyer, Desbrun, Schröder, Barr 2003):
//! mean curvature from the cotangent Laplace–Beltrami operator, Gaussian curvature from the
//! angle defect, both over mixed Voronoi areas; principal curvatures from the two.
struct VertexCurvature {
  std::vector<float> mean;      //!< H, signed: positive where the surface bends away from the normal
  std::vector<float> gaussian;  //!< K
  std::vector<float> k1, k2;    //!< principal curvatures, k1 >= k2 (H ± sqrt(max(H² − K, 0)))
  //! |k1| ≥ |k2| magnitude used by the line pass: max(|k1|, |k2|), in 1/mesh units.
  std::vector<float> magnitude;
};

//! Border vertices get the values of their nearest interior neighbour (their angle defect
//! and Voronoi cells are incomplete). The mesh must be a triangle mesh; degenerate faces
//! contribute nothing.
VertexCurvature estimateCurvature(const Mesh& mesh);

//! Principal curvatures from a quadric z = a x² + b xy + c y² + d x + e y fitted by least
//! squares to the two-ring of each vertex in its tangent frame (degree-2 jet fitting, as
//! CGAL's Monge_via_jet_fitting does). Slower than the cotangent estimator but robust on
//! irregular meshes, where cotangent weights of obtuse triangles give outliers. Vertices
//! with fewer than six two-ring neighbours, and border vertices, fall back as in
//! estimateCurvature. `mean` and `gaussian` are (k1 + k2) / 2 and k1·k2 of the fit.
VertexCurvature estimateCurvatureByFit(const Mesh& mesh);

//! A length that makes curvature dimensionless: 1 / (the `percentile` of |k| over the
//! vertices, area-weighted), as rtsc does, so `curve_factor` means the same on any mesh.
//! percentile in (0, 100); returns 0 for a flat mesh.
double curvatureFeatureSize(const Mesh& mesh, const VertexCurvature& curvature, double percentile = 90.0);

//! `iterations` Jacobi sweeps of the one-ring mean (each vertex and its edge neighbours,
//! equal weights) over a per-vertex field: curvature at the scale of major landforms rather
//! than of the mesh's finest roughness. Keeps constants; on a regular grid it keeps linear
//! fields at interior vertices. The field's size must be the vertex count.
void smoothOverOneRing(const Mesh& mesh, std::vector<float>& field, int iterations);

}  // namespace shanshui::mesh
