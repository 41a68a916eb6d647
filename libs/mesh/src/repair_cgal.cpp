// The mesh repair pipeline on CGAL's Polygon Mesh Processing. This is the only file of
// libs/mesh that includes CGAL: the interface (repair.h) speaks shanshui types only.
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_set>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include "shanshui/core/error.h"
#include "shanshui/mesh/repair.h"

namespace shanshui::mesh {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Halfedge = SurfaceMesh::Halfedge_index;
namespace PMP = CGAL::Polygon_mesh_processing;
using Polygon = std::vector<std::size_t>;

// Removes repeated consecutive (cyclic) indices; false if fewer than three remain.
bool simplifyPolygon(Polygon& p) {
  Polygon out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (out.empty() || out.back() != p[i]) out.push_back(p[i]);
  }
  while (out.size() > 1 && out.front() == out.back()) out.pop_back();
  p = std::move(out);
  std::unordered_set<std::size_t> distinct(p.begin(), p.end());
  return distinct.size() >= 3;
}

std::size_t simplifyPolygons(std::vector<Polygon>& polygons) {
  std::size_t removed = 0;
  std::vector<Polygon> kept;
  kept.reserve(polygons.size());
  for (Polygon& p : polygons) {
    if (simplifyPolygon(p))
      kept.push_back(std::move(p));
    else
      ++removed;
  }
  polygons = std::move(kept);
  return removed;
}

struct BorderLoop {
  Halfedge start;
  std::size_t edges = 0;
  double length = 0.0;
};

std::vector<BorderLoop> borderLoops(const SurfaceMesh& sm) {
  std::vector<BorderLoop> loops;
  std::unordered_set<std::size_t> seen;
  for (Halfedge h : sm.halfedges()) {
    if (!sm.is_border(h) || seen.count(h.idx())) continue;
    BorderLoop loop{h, 0, 0.0};
    Halfedge c = h;
    do {
      seen.insert(c.idx());
      ++loop.edges;
      loop.length += std::sqrt(CGAL::to_double(CGAL::squared_distance(sm.point(sm.source(c)), sm.point(sm.target(c)))));
      c = sm.next(c);
    } while (c != h);
    loops.push_back(loop);
  }
  return loops;
}

// Gives each corner of `out` the UV of the soup corner at the same position in the soup face
// with the same corner positions (or, for a triangle the repair made, of any soup vertex at
// that position), then splits every vertex whose corners disagree into one copy per UV.
// Positions are compared exactly: repair merges only identical points. Returns the copies.
std::size_t carryUvsByCorner(const PolygonSoup& soup, Mesh& out) {
  using Key = std::array<double, 3>;
  auto key = [](const glm::dvec3& p) { return Key{p.x, p.y, p.z}; };
  std::map<Key, std::uint32_t> anyAt;
  for (std::uint32_t v = 0; v < soup.positions.size(); ++v) anyAt.emplace(key(soup.positions[v]), v);
  std::map<std::array<Key, 3>, std::size_t> triangleAt;  // sorted corner positions -> soup face
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    if (face.size() != 3 ||
        std::any_of(face.begin(), face.end(), [&](std::uint32_t v) { return v >= soup.positions.size(); }))
      continue;
    std::array<Key, 3> k{key(soup.positions[face[0]]), key(soup.positions[face[1]]), key(soup.positions[face[2]])};
    std::sort(k.begin(), k.end());
    triangleAt.emplace(k, f);
  }
  std::vector<std::vector<std::pair<glm::vec2, std::uint32_t>>> uvsAt(out.positions.size());  // (uv, copy)
  out.uvs.assign(out.positions.size(), glm::vec2(0.0f));
  std::size_t copies = 0;
  for (glm::uvec3& t : out.triangles) {
    std::array<Key, 3> k{key(out.positions[t.x]), key(out.positions[t.y]), key(out.positions[t.z])};
    std::sort(k.begin(), k.end());
    const auto face = triangleAt.find(k);
    for (int c = 0; c < 3; ++c) {
      const Key p = key(out.positions[t[c]]);
      std::uint32_t source = anyAt.at(p);
      if (face != triangleAt.end()) {
        for (std::uint32_t v : soup.faces[face->second])
          if (key(soup.positions[v]) == p) source = v;
      }
      const glm::vec2 uv = soup.uvs[source];
      auto& seen = uvsAt[t[c]];
      const auto same = std::find_if(seen.begin(), seen.end(), [&](const auto& e) { return e.first == uv; });
      if (same != seen.end()) {
        t[c] = same->second;
      } else if (seen.empty()) {
        seen.emplace_back(uv, t[c]);
        out.uvs[t[c]] = uv;
      } else {
        const auto copy = static_cast<std::uint32_t>(out.positions.size());
        out.positions.push_back(out.positions[t[c]]);
        out.normals.push_back(out.normals[t[c]]);
        out.uvs.push_back(uv);
        seen.emplace_back(uv, copy);
        t[c] = copy;
        ++copies;
      }
    }
  }
  return copies;
}

// shanshui's triangles from a triangulated surface mesh.
Mesh toMesh(const SurfaceMesh& sm) {
  Mesh out;
  out.positions.reserve(sm.number_of_vertices());
  for (auto v : sm.vertices()) {
    const Point& p = sm.point(v);
    out.positions.emplace_back(p.x(), p.y(), p.z());
  }
  for (auto f : sm.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[k++] = static_cast<unsigned>(v.idx());
    SHANSHUI_CHECK_EQ(k, 3);
    out.triangles.push_back(t);
  }
  return out;
}

// What the final check can still find: a quad whose triangulating diagonal joins two
// vertices already joined by an edge (a folded quad in a low-poly head) leaves that pair in
// three or four triangles, which a halfedge mesh holds as two edges but a triangle list
// cannot. The triangles go through the soup orientation once more, which duplicates the
// points where fans cannot agree; returns how many points it added, and the border loops.
std::size_t splitWhatStaysNonManifold(Mesh& m, std::size_t* loops) {
  std::vector<Point> points;
  points.reserve(m.positions.size());
  for (const glm::dvec3& p : m.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<Polygon> polygons;
  polygons.reserve(m.triangles.size());
  for (const glm::uvec3& t : m.triangles) polygons.push_back({t[0], t[1], t[2]});
  const std::size_t before = points.size();
  PMP::orient_polygon_soup(points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return 0;
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  const std::size_t added = points.size() - before + PMP::duplicate_non_manifold_vertices(sm);
  m = toMesh(sm);
  *loops = borderLoops(sm).size();
  return added;
}

}  // namespace

bool RepairReport::changed() const {
  for (const auto& [name, value] : counters()) {
    if (name != "boundary_loops" && value != 0.0) return true;
  }
  return false;
}

std::vector<std::pair<std::string, double>> RepairReport::counters() const {
  auto d = [](auto v) { return static_cast<double>(v); };
  return {{"non_finite_vertices", d(non_finite_vertices)},
          {"invalid_faces_removed", d(invalid_faces_removed)},
          {"duplicate_points_merged", d(duplicate_points_merged)},
          {"duplicate_faces_removed", d(duplicate_faces_removed)},
          {"isolated_vertices_removed", d(isolated_vertices_removed)},
          {"non_manifold_vertices_split", d(non_manifold_vertices_split)},
          {"orientation_fixed", d(orientation_fixed)},
          {"faces_triangulated", d(faces_triangulated)},
          {"non_manifold_edges_split", d(non_manifold_edges_split)},
          {"non_manifold_edges_left", d(left.edges_over_two_faces + left.edges_same_direction)},
          {"pinched_vertices_left", d(left.pinched_vertices)},
          {"degenerate_faces_removed", d(degenerate_faces_removed)},
          {"components_removed", d(components_removed)},
          {"holes_filled", d(holes_filled)},
          {"hole_faces_added", d(hole_faces_added)},
          {"holes_left_open", d(holes_left_open)},
          {"uv_seam_vertices_split", d(uv_seam_vertices_split)},
          {"boundary_loops", d(boundary_loops)}};
}

std::string RepairReport::summary() const {
  std::ostringstream s;
  s << input_vertices << " vertices / " << input_faces << " faces in, " << output_vertices << " / " << output_faces
    << " out";
  bool any = false;
  for (const auto& [name, value] : counters()) {
    if (value == 0.0 || name == "boundary_loops") continue;
    s << (any ? ", " : "; ") << name << "=" << value;
    any = true;
  }
  if (!any) s << "; nothing to repair";
  s << "; " << (boundary_loops == 0 ? std::string("closed") : std::to_string(boundary_loops) + " boundary loop(s)");
  if (attributes_dropped) s << "; UVs/normals dropped";
  return s.str();
}

Mesh repairMesh(const PolygonSoup& soup, const RepairOptions& options, RepairReport* reportOut,
                const std::string& name) {
  if (options.max_hole_edges < 3) {
    throw makeError(name, ": max_hole_edges = ", options.max_hole_edges, " (expected >= 3)");
  }
  RepairReport r;
  r.input_vertices = soup.positions.size();
  r.input_faces = soup.faces.size();

  // 1. Non-finite vertices go, with every face that uses them.
  std::vector<std::size_t> remap(soup.positions.size(), SIZE_MAX);
  std::vector<Point> points;
  points.reserve(soup.positions.size());
  for (std::size_t i = 0; i < soup.positions.size(); ++i) {
    const glm::dvec3& p = soup.positions[i];
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) {
      remap[i] = points.size();
      points.emplace_back(p.x, p.y, p.z);
    } else {
      ++r.non_finite_vertices;
    }
  }
  std::vector<Polygon> polygons;
  polygons.reserve(soup.faces.size());
  for (const auto& f : soup.faces) {
    Polygon p;
    bool ok = true;
    for (std::uint32_t i : f) {
      if (i >= remap.size() || remap[i] == SIZE_MAX) {
        ok = false;
        break;
      }
      p.push_back(remap[i]);
    }
    if (ok)
      polygons.push_back(std::move(p));
    else
      ++r.invalid_faces_removed;
  }
  r.invalid_faces_removed += simplifyPolygons(polygons);

  // 2. Soup clean-up: merge coincident points, drop faces that collapse, duplicates, strays.
  r.duplicate_points_merged = PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  r.invalid_faces_removed += simplifyPolygons(polygons);
  r.duplicate_faces_removed = PMP::merge_duplicate_polygons_in_polygon_soup(points, polygons);
  r.isolated_vertices_removed = PMP::remove_isolated_points_in_polygon_soup(points, polygons);
  if (polygons.empty()) {
    throw makeError(name, ": no valid faces (", soup.faces.size(), " faces read, ", r.invalid_faces_removed,
                    " invalid or degenerate, ", r.non_finite_vertices, " non-finite vertices)");
  }
  const bool attributesFollow = r.non_finite_vertices == 0 && r.invalid_faces_removed == 0 &&
                                r.duplicate_points_merged == 0 && r.duplicate_faces_removed == 0 &&
                                r.isolated_vertices_removed == 0;

  // 3. Consistent orientation; points shared by incompatible fans are duplicated.
  const std::vector<Polygon> before = polygons;
  const std::size_t pointsBefore = points.size();
  PMP::orient_polygon_soup(points, polygons);
  r.non_manifold_vertices_split = points.size() - pointsBefore;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    // Duplicated points keep their coordinates, so compare positions, not indices.
    for (std::size_t k = 0; k < polygons[i].size(); ++k) {
      if (points[polygons[i][k]] != points[before[i][k]]) {
        r.orientation_fixed = true;
        break;
      }
    }
  }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    throw makeError(name, ": cannot be made into a manifold surface after orientation");
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  r.non_manifold_vertices_split += PMP::duplicate_non_manifold_vertices(sm);

  // 4. Triangles only.
  for (auto f : sm.faces()) {
    if (sm.degree(f) > 3) ++r.faces_triangulated;
  }
  if (r.faces_triangulated > 0 && !PMP::triangulate_faces(sm)) {
    r.warnings.push_back("some polygons could not be triangulated");
  }

  // 5. Zero-area triangles.
  const std::size_t facesBefore = sm.number_of_faces();
  PMP::remove_degenerate_faces(sm);
  sm.collect_garbage();
  r.degenerate_faces_removed = facesBefore - sm.number_of_faces();
  if (sm.number_of_faces() == 0) throw makeError(name, ": every face is degenerate (zero area)");

  // 6. Connected components.
  auto faceComponent = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:cc").first;
  const std::size_t components = PMP::connected_components(sm, faceComponent);
  if (components > 1) {
    if (options.components == ComponentPolicy::Fail) {
      throw makeError(name, ": has ", components, " connected components (expected one)");
    }
    if (options.components == ComponentPolicy::KeepLargest) {
      r.components_removed = PMP::keep_largest_connected_components(sm, 1);
      sm.collect_garbage();
      r.warnings.push_back("dropped " + std::to_string(r.components_removed) + " smaller connected component(s)");
    }
  }
  sm.remove_property_map(faceComponent);

  // 7. Holes: every border loop but, per connected component, the longest one (that
  //    component's outer border) when asked.
  if (options.fill_holes) {
    const std::vector<BorderLoop> loops = borderLoops(sm);
    std::vector<bool> isOuter(loops.size(), false);
    if (options.keep_outer_boundary) {
      auto component = sm.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:cc2").first;
      PMP::connected_components(sm, component);
      std::map<std::size_t, std::size_t> longest;  // component -> loop index
      for (std::size_t i = 0; i < loops.size(); ++i) {
        const std::size_t c = component[sm.face(sm.opposite(loops[i].start))];
        const auto it = longest.find(c);
        if (it == longest.end() || loops[i].length > loops[it->second].length) longest[c] = i;
      }
      for (const auto& [c, i] : longest) isOuter[i] = true;
      sm.remove_property_map(component);
    }
    for (std::size_t i = 0; i < loops.size(); ++i) {
      if (isOuter[i]) continue;
      if (loops[i].edges > static_cast<std::size_t>(options.max_hole_edges)) {
        ++r.holes_left_open;
        continue;
      }
      std::vector<SurfaceMesh::Face_index> added;
      PMP::triangulate_hole(sm, loops[i].start, std::back_inserter(added));
      if (added.empty()) {
        ++r.holes_left_open;
      } else {
        ++r.holes_filled;
        r.hole_faces_added += added.size();
      }
    }
    if (r.holes_left_open > 0) {
      r.warnings.push_back(std::to_string(r.holes_left_open) + " hole(s) left open");
    }
  }
  sm.collect_garbage();

  // A closed surface should face outwards.
  if (CGAL::is_closed(sm) && !PMP::is_outward_oriented(sm)) {
    PMP::reverse_face_orientations(sm);
    r.orientation_fixed = true;
  }

  // 8. Back to shanshui's types.
  Mesh out = toMesh(sm);
  r.boundary_loops = borderLoops(sm).size();
  // The final check, on the triangles handed back: a vertex pair in more than two triangles
  // (a triangulated diagonal on an existing edge) or a pinched vertex is split apart once
  // more, and a mesh that still fails is refused rather than handed on.
  if (const ManifoldProblems found = manifoldProblems(out); found.any()) {
    const std::size_t added = splitWhatStaysNonManifold(out, &r.boundary_loops);
    r.non_manifold_vertices_split += added;
    r.non_manifold_edges_split = found.edges_over_two_faces + found.edges_same_direction;
    r.warnings.push_back("split " + std::to_string(r.non_manifold_edges_split) + " non-manifold edge(s) and " +
                         std::to_string(found.pinched_vertices) + " pinched vertex(es) left after triangulation (" +
                         std::to_string(added) + " vertices added)");
  }
  r.left = manifoldProblems(out);
  if (r.left.any()) {
    throw makeError(name, ": cannot be made manifold: ", r.left.edges_over_two_faces,
                    " edge(s) in more than two faces, ", r.left.edges_same_direction,
                    " edge(s) with disagreeing orientation, ", r.left.pinched_vertices,
                    " pinched vertex(es) remain after repair");
  }
  r.output_vertices = out.positions.size();
  r.output_faces = out.triangles.size();
  // UVs or normals with a NaN or an infinity (a PLY's NaN u, an OBJ's vt 1e300 beyond a
  // float) cannot be carried: they are dropped, and said so.
  auto allFinite = [](const auto& values) {
    return std::all_of(values.begin(), values.end(), [](const auto& v) {
      for (int k = 0; k < v.length(); ++k)
        if (!std::isfinite(v[k])) return false;
      return true;
    });
  };
  const bool finiteUvs = allFinite(soup.uvs), finiteNormals = allFinite(soup.normals);
  if (!finiteUvs || !finiteNormals) {
    r.warnings.push_back(std::string("non-finite ") + (!finiteUvs ? "UVs" : "normals") + " in the input were dropped");
  }
  const bool sameVertices = attributesFollow && out.positions.size() == soup.positions.size() &&
                            r.non_manifold_vertices_split == 0 && r.components_removed == 0;
  if (sameVertices) {
    if (finiteUvs) out.uvs = soup.uvs;
    if (finiteNormals) out.normals = soup.normals;
  } else if (finiteUvs && soup.uvs.size() == soup.positions.size() && !soup.uvs.empty()) {
    // UVs with seams (a chart atlas, a sphere cut open) come as coincident vertices that
    // step 2 merged: they follow the corners, and seams are split again.
    out.normals = vertexNormals(out);
    r.uv_seam_vertices_split = carryUvsByCorner(soup, out);
  } else {
    r.attributes_dropped = !soup.uvs.empty() || !soup.normals.empty();
  }
  if (out.normals.empty()) out.normals = vertexNormals(out);
  if (reportOut) *reportOut = r;
  return out;
}

Mesh subdivideLoop(const Mesh& m, int iterations, const std::string& what) {
  if (iterations < 0 || iterations > kMostSubdivisions) {
    throw makeError(what, ": ", iterations, " Loop subdivisions; expected a whole number from 0 to ",
                    kMostSubdivisions);
  }
  if (iterations == 0) return m;
  const std::size_t made = m.triangles.size() << (2 * iterations);
  if (made > kMostSubdividedTriangles) {
    throw makeError(what, ": ", m.triangles.size(), " triangles ", iterations, " times Loop-subdivided would be ", made,
                    ", more than the ", kMostSubdividedTriangles, " this makes");
  }
  std::vector<Point> points;
  points.reserve(m.positions.size());
  for (const glm::dvec3& p : m.positions) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(m.triangles.size());
  for (const glm::uvec3& t : m.triangles) faces.push_back({t.x, t.y, t.z});
  if (faces.empty() || !PMP::is_polygon_soup_a_polygon_mesh(faces)) {
    throw makeError(what, ": the mesh is not one manifold surface, so it cannot be Loop-subdivided");
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, faces, sm);
  CGAL::Subdivision_method_3::Loop_subdivision(sm, CGAL::parameters::number_of_iterations(iterations));
  Mesh out = toMesh(sm);
  out.normals = vertexNormals(out);
  return out;
}

}  // namespace shanshui::mesh
