// Mesh repair (SPEC.md section 4): everything a raw mesh needs before rendering or
// parameterization, with a report of what was changed.
#pragma once

#include <string>
#include <vector>

#include "shanshui/mesh/mesh.h"

namespace shanshui::mesh {

enum class ComponentPolicy { KeepLargest, Fail, KeepAll };

struct RepairOptions {
  ComponentPolicy components = ComponentPolicy::KeepLargest;  //!< extra connected components
  bool fill_holes = true;                                     //!< fill boundary loops that are holes
  int max_hole_edges = 1000;                                  //!< holes with more boundary edges stay open, [3, inf)
  bool keep_outer_boundary = true;                            //!< the longest boundary loop is the border, not a hole
};

//! Counts of what each repair step changed; all zero when the input was already clean.
struct RepairReport {
  std::size_t input_vertices = 0;
  std::size_t input_faces = 0;
  std::size_t non_finite_vertices = 0;    //!< NaN/Inf positions (their faces are dropped)
  std::size_t invalid_faces_removed = 0;  //!< < 3 distinct vertices, bad indices, NaN
  std::size_t duplicate_points_merged = 0;
  std::size_t duplicate_faces_removed = 0;
  std::size_t isolated_vertices_removed = 0;
  std::size_t non_manifold_vertices_split = 0;
  //! Vertex pairs still in more than two triangles after triangulation, split at the end.
  std::size_t non_manifold_edges_split = 0;
  bool orientation_fixed = false;            //!< some faces were flipped to agree
  std::size_t faces_triangulated = 0;        //!< polygons with more than three sides
  std::size_t degenerate_faces_removed = 0;  //!< zero-area triangles
  std::size_t components_removed = 0;
  std::size_t holes_filled = 0;
  std::size_t hole_faces_added = 0;
  std::size_t holes_left_open = 0;  //!< larger than max_hole_edges, or filling failed
  std::size_t boundary_loops = 0;   //!< in the result; 0 means closed
  bool attributes_dropped = false;  //!< UVs/normals could not follow the changes
  //! UV seams (coincident vertices with different UVs) merged by the clean-up and split
  //! again so that the UVs follow every corner; normals are then recomputed.
  std::size_t uv_seam_vertices_split = 0;
  ManifoldProblems left;  //!< what the final check finds: always none (repair refuses otherwise)
  std::size_t output_vertices = 0;
  std::size_t output_faces = 0;
  std::vector<std::string> warnings;

  bool changed() const;
  //! "name=value" lines of the non-zero counters, for logs and reports.
  std::vector<std::pair<std::string, double>> counters() const;
  std::string summary() const;
};

//! Repairs a polygon soup into a triangle mesh: drops non-finite vertices and invalid
//! faces, merges duplicate points and faces, orients consistently, splits non-manifold
//! vertices, triangulates, removes degenerate faces, handles extra components by policy
//! and fills holes. Throws Error when nothing usable is left (no faces) or the policy
//! asks to fail. `name` prefixes the messages.
Mesh repairMesh(const PolygonSoup& soup, const RepairOptions& options, RepairReport* report,
                const std::string& name = "mesh");

//! Most Loop subdivision steps subdivideLoop takes (each makes four triangles of one), and
//! the most triangles it makes.
constexpr int kMostSubdivisions = 4;
constexpr std::size_t kMostSubdividedTriangles = std::size_t{1} << 24;

//! The triangle mesh `iterations` times Loop-subdivided (CGAL::Subdivision_method_3; the
//! border as a cubic B-spline): each step makes four triangles of one and moves the
//! vertices towards the smooth limit surface, so a low-poly land's facets and their creases
//! become rounded ground. Vertex normals are made anew; UVs are dropped (they would need
//! their seams subdivided with them). iterations 0: `m` as it is. Throws Error naming `what`
//! for iterations outside [0, kMostSubdivisions], a result over kMostSubdividedTriangles, or
//! a mesh that is no manifold surface.
Mesh subdivideLoop(const Mesh& m, int iterations, const std::string& what);

}  // namespace shanshui::mesh
