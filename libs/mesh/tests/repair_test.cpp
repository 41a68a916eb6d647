#include "shanshui/mesh/repair.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "mesh_checks.h"
#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::mesh {
namespace {

RepairReport repairFile(const char* name, Mesh* out = nullptr, RepairOptions options = {}) {
  const auto path = test::cgalMeshes() / name;
  RepairReport r;
  const Mesh m = repairMesh(readPolygonSoup(path), options, &r, path.string());
  test::expectCleanMesh(m, name);
  EXPECT_EQ(r.output_faces, m.triangles.size());
  if (out) *out = m;
  return r;
}

#define REQUIRE_CGAL_MESH(name) SHANSHUI_REQUIRE_FILE(test::cgalMeshes() / name)

TEST(Repair, EveryCgalTestMeshComesOutClean) {
  REQUIRE_CGAL_MESH("bear.off");
  for (const auto& entry : std::filesystem::directory_iterator(test::cgalMeshes())) {
    repairFile(entry.path().filename().c_str());
  }
}

// Issue 48: a PLY's NaN u/v, or an OBJ's vt beyond a float, was copied into the output.
TEST(Repair, NonFiniteUvsAndNormalsAreDroppedAndSaidSo) {
  const Mesh cube = unitCube();
  PolygonSoup soup;
  soup.positions = cube.positions;
  for (const glm::uvec3& t : cube.triangles) soup.faces.push_back({t.x, t.y, t.z});
  soup.uvs.assign(soup.positions.size(), glm::vec2(0.25f, 0.75f));
  soup.uvs[2].x = std::nanf("");
  RepairReport r;
  const Mesh out = repairMesh(soup, RepairOptions{}, &r, "nan.ply");
  EXPECT_TRUE(out.uvs.empty());
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("non-finite UVs"), std::string::npos) << r.warnings.back();
  EXPECT_NO_THROW(encodeMesh(out, "fixed.obj"));
  soup.uvs.clear();
  soup.normals.assign(soup.positions.size(), glm::vec3(0, 0, 1));
  soup.normals[5].y = std::numeric_limits<float>::infinity();
  const Mesh n = repairMesh(soup, RepairOptions{}, nullptr, "inf.ply");
  for (const glm::vec3& v : n.normals) EXPECT_TRUE(std::isfinite(v.x + v.y + v.z));
}

TEST(Repair, CleanMeshesAreLeftAlone) {
  REQUIRE_CGAL_MESH("three_peaks.off");
  for (const char* name : {"three_peaks.off", "triceratops.off", "anchor.off"}) {
    const RepairReport r = repairFile(name);
    EXPECT_FALSE(r.changed()) << name << ": " << r.summary();
  }
  EXPECT_EQ(repairFile("three_peaks.off").boundary_loops, 1u);  // a terrain disc
}

TEST(Repair, ClosedMeshStaysClosedAndFacesOutwards) {
  REQUIRE_CGAL_MESH("bear.off");
  Mesh m;
  const RepairReport r = repairFile("bear.off", &m);
  EXPECT_EQ(r.boundary_loops, 0u);
  EXPECT_EQ(test::meshFacts(m).boundary_edges, 0u);
  EXPECT_GT(test::meshFacts(m).signed_volume, 0.0);
}

TEST(Repair, HolesAreFilledButTheOuterBorderIsKept) {
  REQUIRE_CGAL_MESH("holes.off");
  for (const char* name : {"holes.off", "lion.off", "elephant-with-holes.off"}) {
    const RepairReport r = repairFile(name);
    EXPECT_GT(r.holes_filled, 0u) << name;
    EXPECT_EQ(r.boundary_loops, 1u) << name;
  }
  RepairOptions noFill;
  noFill.fill_holes = false;
  EXPECT_GT(repairFile("holes.off", nullptr, noFill).boundary_loops, 1u);
}

TEST(Repair, ExtraComponentsFollowThePolicy) {
  REQUIRE_CGAL_MESH("blobby_3cc.off");
  EXPECT_EQ(repairFile("blobby_3cc.off").components_removed, 2u);
  RepairOptions fail;
  fail.components = ComponentPolicy::Fail;
  const auto path = test::cgalMeshes() / "blobby_3cc.off";
  try {
    repairMesh(readPolygonSoup(path), fail, nullptr, path.string());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("3 connected components"), std::string::npos) << e.what();
  }
  RepairOptions all;
  all.components = ComponentPolicy::KeepAll;
  EXPECT_EQ(repairFile("blobby_3cc.off", nullptr, all).components_removed, 0u);
}

TEST(Repair, DegenerateQuadShuffledAndStrayInputsAreFixed) {
  REQUIRE_CGAL_MESH("degtri_sliding.off");
  EXPECT_GT(repairFile("degtri_sliding.off").degenerate_faces_removed, 0u);
  EXPECT_TRUE(repairFile("oblong-shuffled.off").orientation_fixed);
  EXPECT_EQ(repairFile("cube-ouvert.off").isolated_vertices_removed, 1u);
  const RepairReport quads = repairFile("cube_quad.off");
  EXPECT_EQ(quads.faces_triangulated, 6u);
  EXPECT_EQ(quads.output_faces, 12u);
}

TEST(Repair, NanVerticesBowTiesAndDuplicatesInASoup) {
  PolygonSoup s;
  // Two triangles touching only at vertex 0 (a pinched, non-manifold vertex), a NaN
  // vertex with its face, a duplicate face and a face that repeats a vertex.
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}, {NAN, 0, 0}};
  s.faces = {{0, 1, 2}, {0, 3, 4}, {0, 1, 5}, {0, 1, 2}, {1, 1, 2}};
  RepairOptions keepAll;
  keepAll.components = ComponentPolicy::KeepAll;
  RepairReport r;
  const Mesh m = repairMesh(s, keepAll, &r);
  test::expectCleanMesh(m, "bow-tie");
  EXPECT_EQ(r.non_finite_vertices, 1u);
  EXPECT_EQ(r.invalid_faces_removed, 2u);  // the NaN face and {1,1,2}
  EXPECT_EQ(r.duplicate_faces_removed, 1u);
  EXPECT_EQ(r.non_manifold_vertices_split, 1u);
  EXPECT_EQ(r.holes_filled, 0u);  // each component keeps its own outer border
  EXPECT_EQ(r.boundary_loops, 2u);
  EXPECT_EQ(m.triangles.size(), 2u);
}

TEST(Repair, NothingUsableIsAClearError) {
  PolygonSoup s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  s.faces = {{0, 1, 2}};  // collinear: zero area
  EXPECT_THROW(repairMesh(s, {}, nullptr, "line.obj"), Error);
  s.faces.clear();
  try {
    repairMesh(s, {}, nullptr, "nofaces.obj");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("nofaces.obj: no valid faces"), std::string::npos) << e.what();
  }
}

TEST(Repair, SingleTriangleAndHugeCoordinatesSurvive) {
  PolygonSoup s;
  s.positions = {{557945.011821133, 5107991.33901730, 682.0},
                 {557975.011821133, 5107991.33901730, 690.0},
                 {557945.011821133, 5108021.33901730, 700.0}};
  s.faces = {{0, 1, 2}};
  s.uvs = {{0, 0}, {1, 0}, {0, 1}};
  RepairReport r;
  const Mesh m = repairMesh(s, {}, &r);
  test::expectCleanMesh(m, "one triangle");
  EXPECT_FALSE(r.changed());
  EXPECT_EQ(m.positions, s.positions);  // untouched, so attributes follow
  EXPECT_EQ(m.uvs, s.uvs);
}

// The outside test's monkey head kept one non-manifold edge: a quad whose triangulating
// diagonal joins two vertices that other faces already join. Here a quad (a, b, c, d) is
// closed by two triangles over its halves (a, d, c) and (c, b, a): a closed manifold
// polygon mesh, until the quad is cut along its short diagonal a-c, which then lies in
// four triangles. Repair must split it and end manifold, keeping every triangle.
TEST(Repair, ADiagonalOnAnExistingEdgeIsSplitNotHandedOn) {
  PolygonSoup s;
  s.positions = {{-1, 0, 0}, {0, -3, 0.5}, {1, 0, 0}, {0, 3, 0.5}};
  s.faces = {{0, 1, 2, 3}, {0, 3, 2}, {2, 1, 0}};
  RepairReport r;
  RepairOptions keepAll;
  keepAll.components = ComponentPolicy::KeepAll;
  keepAll.fill_holes = false;
  const Mesh m = repairMesh(s, keepAll, &r, "pillow");
  EXPECT_EQ(r.faces_triangulated, 1u);
  EXPECT_GE(r.non_manifold_edges_split, 1u) << r.summary();
  EXPECT_FALSE(r.left.any()) << r.summary();
  EXPECT_FALSE(manifoldProblems(m).any()) << "the oracle on the triangles handed back";
  EXPECT_EQ(m.triangles.size(), 4u) << "nothing removed";
  test::expectCleanMesh(m, "pillow");
}

}  // namespace
}  // namespace shanshui::mesh

namespace shanshui::mesh {
namespace {

// manifoldProblems() against the map-based oracle of mesh_checks.h on random triangle
// lists (many shared, repeated and reversed edges), and on pinched vertices built by hand.
TEST(ManifoldCheck, AgreesWithTheOracleAndFindsPinchedVertices) {
  std::mt19937 rng(5);
  for (int round = 0; round < 50; ++round) {
    Mesh m;
    m.positions.resize(8);
    std::uniform_int_distribution<unsigned> vertex(0, 7);
    for (int t = 0; t < 12; ++t) {
      glm::uvec3 tri(vertex(rng), vertex(rng), vertex(rng));
      if (tri.x == tri.y || tri.y == tri.z || tri.x == tri.z) continue;
      m.triangles.push_back(tri);
    }
    const test::MeshFacts facts = test::meshFacts(m);
    const ManifoldProblems found = manifoldProblems(m);
    EXPECT_EQ(found.edges_over_two_faces, facts.non_manifold_edges) << round;
    // The oracle counts directed duplicates; among edges with exactly two uses they agree.
    EXPECT_LE(found.edges_same_direction, facts.inconsistent_edges) << round;
  }
  Mesh bowTie;  // two triangles meeting only at vertex 0
  bowTie.positions.resize(5);
  bowTie.triangles = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(manifoldProblems(bowTie).pinched_vertices, 1u);
  Mesh fan;  // a closed fan of four triangles around vertex 0: not pinched
  fan.positions.resize(5);
  fan.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
  EXPECT_FALSE(manifoldProblems(fan).any());
  Mesh flipped = fan;  // one triangle turned over
  std::swap(flipped.triangles[1].y, flipped.triangles[1].z);
  EXPECT_EQ(manifoldProblems(flipped).edges_same_direction, 2u);
}

// Quads folded back onto each other (as in a low-poly head): exactly, nearly, crossing
// through, and a third quad on the shared edge. Repair ends with a mesh that passes its own
// check and the oracle, and is then a disc or says why not.
TEST(Repair, FoldedQuadsEndManifold) {
  const std::vector<std::vector<glm::dvec3>> folds = {
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {1, 1, 0}, {1, 0, 0}},        // folded flat
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {1, 1, 1e-3}, {1, 0, 1e-3}},  // nearly
      {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {0.5, 1, 0.5}, {1.5, 0, -0.5}}};
  for (std::size_t i = 0; i < folds.size(); ++i) {
    for (bool third : {false, true}) {
      PolygonSoup s;
      s.positions = folds[i];
      s.faces = {{0, 1, 2, 3}, {1, 0, 5, 4}};
      if (third) {
        s.positions.push_back({-1, 1, 0});
        s.positions.push_back({-1, 0, 0});
        s.faces.push_back({0, 1, 6, 7});
      }
      RepairReport r;
      RepairOptions keepAll;
      keepAll.components = ComponentPolicy::KeepAll;
      const Mesh m = repairMesh(s, keepAll, &r, "folded");
      SCOPED_TRACE("fold " + std::to_string(i) + (third ? " with a third quad" : ""));
      test::expectCleanMesh(m, "folded");
      EXPECT_FALSE(r.left.any()) << r.summary();
      EXPECT_FALSE(manifoldProblems(m).any());
    }
  }
}

}  // namespace
}  // namespace shanshui::mesh

namespace shanshui::mesh {
namespace {

// A cube whose six sides each have their own UV square (24 vertices, as an atlas writes
// it): the clean-up merges the coincident corners, and the UVs must still follow every
// corner, with the seams split again.
TEST(Repair, UvSeamsSurviveTheMergeOfCoincidentVertices) {
  PolygonSoup soup;
  const glm::dvec3 corner[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int sides[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int s = 0; s < 6; ++s) {
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (int k = 0; k < 4; ++k) {
      soup.positions.push_back(corner[sides[s][k]]);
      soup.uvs.emplace_back(2.0f * s + (k == 1 || k == 2), (k >= 2) ? 1.0f : 0.0f);
    }
    soup.faces.push_back({base, base + 1, base + 2});
    soup.faces.push_back({base, base + 2, base + 3});
  }
  RepairReport r;
  const Mesh m = repairMesh(soup, {}, &r, "cube.obj");
  EXPECT_FALSE(r.attributes_dropped);
  EXPECT_EQ(r.boundary_loops, 0u);           // closed once merged
  EXPECT_EQ(r.uv_seam_vertices_split, 16u);  // 24 corners of 8 points
  ASSERT_EQ(m.uvs.size(), m.positions.size());
  ASSERT_EQ(m.normals.size(), m.positions.size());
  ASSERT_EQ(m.triangles.size(), soup.faces.size());
  // Oracle: every output corner has the UV of the input corner at the same position in the
  // input triangle with the same three positions.
  for (const glm::uvec3& t : m.triangles) {
    bool found = false;
    for (const auto& f : soup.faces) {
      int same = 0;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) same += m.positions[t[k]] == soup.positions[f[l]];
      if (same != 3) continue;
      found = true;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          if (m.positions[t[k]] == soup.positions[f[l]]) {
            EXPECT_EQ(m.uvs[t[k]], soup.uvs[f[l]]);
          }
    }
    EXPECT_TRUE(found);
  }
  // Copies of a corner share its (smooth) normal.
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    for (std::size_t j = i + 1; j < m.positions.size(); ++j)
      if (m.positions[i] == m.positions[j]) {
        EXPECT_EQ(m.normals[i], m.normals[j]);
      }
}

}  // namespace
}  // namespace shanshui::mesh

namespace shanshui::mesh {
namespace {

// The largest angle (degrees) between the normals of two triangles that share an edge: how
// sharp the mesh's sharpest crease is.
double sharpestCrease(const Mesh& m) {
  std::map<std::pair<unsigned, unsigned>, std::vector<glm::dvec3>> by_edge;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 n =
        glm::normalize(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
    for (int k = 0; k < 3; ++k) {
      const unsigned a = t[k], b = t[(k + 1) % 3];
      by_edge[{std::min(a, b), std::max(a, b)}].push_back(n);
    }
  }
  double worst = 0.0;
  for (const auto& [edge, normals] : by_edge)
    if (normals.size() == 2)
      worst = std::max(worst, glm::degrees(std::acos(std::clamp(glm::dot(normals[0], normals[1]), -1.0, 1.0))));
  return worst;
}

}  // namespace

// Loop subdivision (CGAL) makes four triangles of one and a vertex on every edge: the
// icosahedron (12 vertices, 30 edges, 20 faces) twice gives 162 and 320; a 9 x 9 land grid
// twice, 33 x 33 with its border kept open. The sharpest crease rounds off: the
// icosahedron's 41.8° to under a third, the 90° ridge of a roof-shaped grid to under half.
TEST(Subdivide, LoopMakesFourTrianglesOfOneAndRoundsTheCreases) {
  const Mesh ico = icosphere(0);
  ASSERT_EQ(ico.positions.size(), 12u);
  const Mesh round = subdivideLoop(ico, 2, "icosahedron");
  EXPECT_EQ(round.positions.size(), 162u);
  EXPECT_EQ(round.triangles.size(), 320u);
  EXPECT_EQ(round.normals.size(), round.positions.size());
  EXPECT_NEAR(sharpestCrease(ico), 41.81, 0.01);
  EXPECT_LT(sharpestCrease(round), sharpestCrease(ico) / 3.0) << sharpestCrease(round);

  const Mesh roof = heightGrid(9, 9, 1.0, [](double x, double) { return 4.0 - std::abs(x - 4.0); });
  const Mesh smooth = subdivideLoop(roof, 2, "roof");
  EXPECT_EQ(smooth.positions.size(), 33u * 33u);
  EXPECT_EQ(smooth.triangles.size(), 16 * roof.triangles.size());
  test::expectCleanMesh(smooth, "roof");
  EXPECT_NEAR(sharpestCrease(roof), 90.0, 1e-9);
  EXPECT_LT(sharpestCrease(smooth), 0.5 * sharpestCrease(roof)) << sharpestCrease(smooth);
  EXPECT_EQ(subdivideLoop(roof, 0, "roof").positions, roof.positions);
}

// Three triangles on one edge are no surface to subdivide, and the steps and what they make
// are bounded: each refused by name.
TEST(Subdivide, RefusesANonManifoldMeshAndTooManySteps) {
  Mesh fin;
  fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  test::expectErrorNaming([&] { subdivideLoop(fin, 1, "fin.obj"); }, "fin.obj", "not one manifold surface");
  test::expectErrorNaming([&] { subdivideLoop(icosphere(0), kMostSubdivisions + 1, "objects.0.subdivide"); },
                          "objects.0.subdivide", "from 0 to 4");
  test::expectErrorNaming([&] { subdivideLoop(icosphere(0), -1, "objects.0.subdivide"); }, "objects.0.subdivide",
                          "Loop subdivisions");
  // 69 938 triangles four times would be 17.9 million: refused before any work.
  const Mesh big = heightGrid(188, 188, 1.0, [](double, double) { return 0.0; });
  test::expectErrorNaming([&] { subdivideLoop(big, 4, "big.obj"); }, "big.obj", "more than the 16777216");
}

}  // namespace shanshui::mesh
