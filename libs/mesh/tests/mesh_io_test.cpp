#include "shanshui/mesh/mesh_io.h"

#include <cmath>
#include <fstream>
#include <limits>

#include "shanshui/core/error.h"
#include "test_meshes.h"
#include "test_support.h"

namespace shanshui::mesh {
namespace {

Mesh sphereWithAttributes() {
  Mesh m = test::uvSphere(1234.5678, 12, 24, glm::dvec3(557945.011821133, 5107991.33901730, 682.0));
  for (std::size_t i = 0; i < m.positions.size(); ++i) m.uvs.emplace_back(0.001f * i, 1.0f - 0.002f * i);
  return m;
}

// `ulps`: tinyobjloader parses numbers with its own routine that can be a few units in the
// last place off; our PLY and OFF readers are exact.
void expectSameMesh(const Mesh& a, const PolygonSoup& b, bool attributes, double ulps) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  ASSERT_EQ(a.triangles.size(), b.faces.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double tol = ulps * std::abs(a.positions[i][k]) * std::numeric_limits<double>::epsilon();
      ASSERT_LE(std::abs(a.positions[i][k] - b.positions[i][k]), tol) << i;
    }
  }
  for (std::size_t f = 0; f < a.triangles.size(); ++f) {
    ASSERT_EQ(b.faces[f].size(), 3u);
    for (int k = 0; k < 3; ++k) ASSERT_EQ(a.triangles[f][k], b.faces[f][k]);
  }
  if (attributes) {
    ASSERT_EQ(b.uvs.size(), a.uvs.size());
    ASSERT_EQ(b.normals.size(), a.normals.size());
    for (std::size_t i = 0; i < a.uvs.size(); ++i) {
      EXPECT_EQ(a.uvs[i], b.uvs[i]);
      EXPECT_EQ(a.normals[i], b.normals[i]);
    }
  }
}

TEST(MeshIo, RoundTripsKeepDoublePositionsAndAttributes) {
  test::TempDir dir;
  const Mesh m = sphereWithAttributes();
  for (const char* ext : {".obj", ".ply", ".off"}) {
    SCOPED_TRACE(ext);
    const auto path = dir / (std::string("sphere") + ext);
    writeMesh(m, path);
    // UTM-sized coordinates come back bit for bit; OFF stores no attributes.
    const bool obj = std::string(ext) == ".obj";
    expectSameMesh(m, readPolygonSoup(path), std::string(ext) != ".off", obj ? 4.0 : 0.0);
  }
}

TEST(MeshIo, ObjSplitsVerticesWithDifferentUvs) {
  test::TempDir dir;
  std::ofstream(dir / "seam.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                                     "f 1/1 2/2 3/3\nf 1/5 3/3 4/4\n";  // vertex 1 has two UVs
  const PolygonSoup s = readPolygonSoup(dir / "seam.obj");
  EXPECT_EQ(s.positions.size(), 5u);
  EXPECT_EQ(s.uvs.size(), 5u);
  EXPECT_EQ(s.positions[0], s.positions[4]);  // the copy is appended; file order is kept
  EXPECT_EQ(s.uvs[4], glm::vec2(0.5f, 0.5f));
  EXPECT_EQ(s.uvs[0], glm::vec2(0.0f, 0.0f));
  EXPECT_EQ(s.faces[1][0], 4u);
}

TEST(MeshIo, ReadsPolygonsAndOffColours) {
  test::TempDir dir;
  std::ofstream(dir / "quad.off") << "OFF\n# a comment\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n";
  const PolygonSoup s = readPolygonSoup(dir / "quad.off");
  ASSERT_EQ(s.faces.size(), 1u);
  EXPECT_EQ(s.faces[0].size(), 4u);
  std::ofstream(dir / "quad.ply") << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                                     "property float y\nproperty float z\nelement face 1\n"
                                     "property list uchar int vertex_indices\nend_header\n"
                                     "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
  EXPECT_EQ(readPolygonSoup(dir / "quad.ply").faces[0].size(), 4u);
}

TEST(MeshIo, BadInputNamesTheFileAndTheProblem) {
  test::TempDir dir;
  writeMesh(sphereWithAttributes(), dir / "good.ply");
  writeMesh(sphereWithAttributes(), dir / "good.off");
  auto cut = [&](const char* from, const char* to) {
    std::ifstream in(dir / from, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(dir / to, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size() * 2 / 3));
  };
  cut("good.ply", "cut.ply");
  cut("good.off", "cut.off");
  std::ofstream(dir / "nofaces.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  std::ofstream(dir / "badindex.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n";
  std::ofstream(dir / "garbage.off") << "OFF\n3 1 0\n0 0 zero\n";
  std::ofstream(dir / "empty.obj").close();
  std::ofstream(dir / "notes.xyz") << "not a mesh\n";
  // tinyobjloader reads these as 0; the reader must refuse them.
  std::ofstream(dir / "nan.obj") << "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n";
  std::ofstream(dir / "inf.obj") << "# c\nv 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "word.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n";
  // A text PLY may hold any number as an index (the fuzzer's 2.4e124 was cast to 32 bits).
  const std::string ply_header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n";
  std::ofstream(dir / "hugeindex.ply") << ply_header << "3 0 1 2444444444444444444444444444\n";
  std::ofstream(dir / "halfindex.ply") << ply_header << "3 0 1 1.5\n";
  const std::pair<const char*, const char*> cases[] = {
      {"nan.obj", "line 3: vertex coordinate 'nan'"},
      {"inf.obj", "line 3: vertex coordinate 'inf'"},
      {"word.obj", "'zero'"},
      {"missing.obj", "no such file"},
      {"cut.ply", "truncated"},
      {"cut.off", "truncated"},
      {"nofaces.obj", "no faces"},
      {"badindex.off", "vertex 7"},
      {"hugeindex.ply", "face 0: vertex index 2444444"},
      {"halfindex.ply", "vertex index 1.5"},
      {"garbage.off", "'zero'"},
      {"empty.obj", "empty file"},
      {"notes.xyz", "not a mesh format shanshui reads by its extension '.xyz'"}};
  for (const auto& [file, what] : cases) {
    test::expectErrorNaming([&] { readPolygonSoup(dir / file); }, file, what);
  }
  // An element without properties takes no bytes, however many it counts (the fuzzer's three
  // billion ran for minutes): the triangle after it is read.
  std::ofstream(dir / "emptyelement.ply")
      << "ply\nformat ascii 1.0\nelement note 3000000000\n"
      << ply_header.substr(std::string("ply\nformat ascii 1.0\n").size()) << "3 0 1 2\n";
  const PolygonSoup read = readPolygonSoup(dir / "emptyelement.ply");
  EXPECT_EQ(read.positions.size(), 3u);
  ASSERT_EQ(read.faces.size(), 1u);
  EXPECT_EQ(read.faces[0], (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(MeshIo, RefusesToWriteAFacelessMeshAndKeepsTheOldFile) {
  test::TempDir dir;
  const Mesh good = test::uvSphere(1.0, 6, 8);
  writeMesh(good, dir / "m.obj");
  EXPECT_THROW(writeMesh(Mesh{}, dir / "m.obj"), Error);
  EXPECT_EQ(readPolygonSoup(dir / "m.obj").faces.size(), good.triangles.size());
}

// Finite or refused (issue 48): a NaN or an infinity never reaches a file.
TEST(MeshIo, RefusesToEncodeNonFiniteNumbers) {
  Mesh m = unitCube();
  m.uvs.assign(m.positions.size(), glm::vec2(0.5f));
  m.uvs[3].y = std::numeric_limits<float>::infinity();
  test::expectErrorNaming([&] { encodeMesh(m, "uv.obj"); }, "uv.obj", "non-finite UV (vertex 4: 0.5 inf)");
  m.uvs.clear();
  m.positions[0].x = std::nan("");
  test::expectErrorNaming([&] { encodeMesh(m, "p.ply"); }, "p.ply", "non-finite position (vertex 1");
  m = unitCube();
  m.normals = vertexNormals(m);
  m.normals[7].z = -std::numeric_limits<float>::infinity();
  test::expectErrorNaming([&] { encodeMesh(m, "n.off"); }, "n.off", "non-finite normal (vertex 8");
}

TEST(MeshGeometry, NormalsOfASpherePointOutwardsAndRecentreIsExact) {
  Mesh m = test::uvSphere(2.0, 24, 48, glm::dvec3(500000.25, 4000000.5, 100.0));
  const auto n = vertexNormals(m);
  const glm::dvec3 c(500000.25, 4000000.5, 100.0);
  for (std::size_t i = 0; i < n.size(); ++i) {
    EXPECT_GT(glm::dot(glm::dvec3(n[i]), glm::normalize(m.positions[i] - c)), 0.99) << i;
  }
  const glm::dvec3 offset = recentre(m);
  EXPECT_NEAR(glm::length(offset - c), 0.0, 1e-6);
  const Bounds b = bounds(m);
  EXPECT_NEAR(b.min.x, -2.0, 1e-6);
  EXPECT_NEAR(b.max.z, 2.0, 1e-9);
}

}  // namespace
}  // namespace shanshui::mesh
