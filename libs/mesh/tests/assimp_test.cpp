// Meshes an artist exports, through Assimp: a box of known size written by Assimp's own
// exporters in every format it writes, read back through shanshui's reader and repair; the
// axes and units files declare; and normals split at creases like a modelling tool's.
#include <sys/stat.h>

#include <fstream>
#include <memory>
#include <regex>
#include <sstream>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include "mesh_checks.h"
#include "shanshui/core/error.h"
#include "shanshui/mesh/mesh_io.h"
#include "shanshui/mesh/repair.h"
#include "shanshui/mesh/shapes.h"
#include "test_support.h"

namespace shanshui::mesh {
namespace {

namespace fs = std::filesystem;

// A box 2 x 3 x 4 (x, y, z) with a corner at (1, 0, -1), as an aiScene of one mesh.
const glm::dvec3 kBoxSize(2, 3, 4), kBoxMin(1, 0, -1);

std::unique_ptr<aiScene> boxScene() {
  const Mesh cube = unitCube();
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode();
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { new aiMesh() };
  aiMesh* m = scene->mMeshes[0];
  m->mMaterialIndex = 0;
  m->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m->mNumVertices = static_cast<unsigned>(cube.positions.size());
  m->mVertices = new aiVector3D[m->mNumVertices];
  for (unsigned v = 0; v < m->mNumVertices; ++v) {
    const glm::dvec3 p = kBoxMin + cube.positions[v] * kBoxSize;
    m->mVertices[v] = aiVector3D(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
  }
  m->mNumFaces = static_cast<unsigned>(cube.triangles.size());
  m->mFaces = new aiFace[m->mNumFaces];
  for (unsigned f = 0; f < m->mNumFaces; ++f) {
    m->mFaces[f].mNumIndices = 3;
    m->mFaces[f].mIndices = new unsigned[3]{cube.triangles[f].x, cube.triangles[f].y, cube.triangles[f].z};
  }
  return scene;
}

// Repaired, its bounds, volume and closedness against the box scaled by `metres`.
void expectBox(const fs::path& f, double metres, const std::string& axes = "xyz") {
  SCOPED_TRACE(f.filename().string());
  const PolygonSoup soup = readPolygonSoup(f);
  const Mesh m = repairMesh(soup, RepairOptions{}, nullptr, f.string());
  const test::MeshFacts facts = test::meshFacts(m);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(facts.boundary_edges, 0u);
  EXPECT_NEAR(facts.signed_volume, 24.0 * metres * metres * metres, 1e-4 * 24 * metres * metres * metres)
      << "closed and outward";
  const Bounds b = bounds(m);
  for (int k = 0; k < 3; ++k) {
    const int from = axes[k] - 'x';
    EXPECT_NEAR(b.size()[k], kBoxSize[from] * metres, 1e-5 * metres) << "axis " << k;
  }
}

// The box written by Assimp's exporter `format` to dir / name, read back as a box, and the
// file's bytes (for the tests that break it).
std::string exportedBox(const fs::path& dir, const char* format, const char* name) {
  Assimp::Exporter exporter;
  EXPECT_EQ(exporter.Export(boxScene().get(), format, (dir / name).string()), AI_SUCCESS);
  expectBox(dir / name, 1.0);
  std::ifstream in(dir / name, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST(AssimpIo, EveryFormatAssimpWritesRoundTripsAKnownBox) {
  test::TempDir dir;
  const auto scene = boxScene();
  Assimp::Exporter exporter;
  // Format id, file name, and the metres one exported unit is read as.
  const struct {
    const char* id;
    const char* file;
    double metres;
  } formats[] = {{"gltf2", "box.gltf", 1.0},
                 {"glb2", "box.glb", 1.0},
                 {"collada", "box.dae", 1.0},
                 {"stl", "box.stl", 1.0},
                 {"stlb", "box_b.stl", 1.0},
                 {"3ds", "box.3ds", 1.0},
                 // Assimp writes FBX with UnitScaleFactor 1: one unit is a centimetre. (Its binary
                 // FBX writer makes files its own 5.2 reader refuses, so the text form is used.)
                 {"fbxa", "box.fbx", 0.01}};
  for (const auto& f : formats) {
    ASSERT_EQ(exporter.Export(scene.get(), f.id, (dir / f.file).string()), AI_SUCCESS)
        << f.id << ": " << exporter.GetErrorString();
    expectBox(dir / f.file, f.metres);
  }
  const PolygonSoup fbx = readPolygonSoup(dir / "box.fbx");
  ASSERT_FALSE(fbx.notes.empty());
  EXPECT_NE(fbx.notes.back().find("cm converted to metres"), std::string::npos) << fbx.notes.back();
}

// COLLADA's <up_axis> and <unit>, and FBX's axis settings, as an artist's tool writes them.
TEST(AssimpIo, DeclaredUpAxisAndUnitsAreHonoured) {
  test::TempDir dir;
  const auto scene = boxScene();
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(scene.get(), "collada", (dir / "y.dae").string()), AI_SUCCESS);
  std::stringstream text;
  text << std::ifstream(dir / "y.dae").rdbuf();
  std::string dae = text.str();
  dae = std::regex_replace(dae, std::regex("<up_axis>Y_UP</up_axis>"), "<up_axis>Z_UP</up_axis>");
  dae = std::regex_replace(dae, std::regex("<unit [^>]*/>"), "<unit name=\"centimeter\" meter=\"0.01\" />");
  ASSERT_NE(dae.find("Z_UP"), std::string::npos);
  std::ofstream(dir / "z_cm.dae") << dae;
  // Z up in the file: its z (4) becomes y, its y (3) becomes z; 1 unit = 1 cm.
  expectBox(dir / "z_cm.dae", 0.01, "xzy");

  ASSERT_EQ(exporter.Export(scene.get(), "fbxa", (dir / "y.fbx").string()), AI_SUCCESS);
  std::stringstream fbxText;
  fbxText << std::ifstream(dir / "y.fbx").rdbuf();
  std::string fbx = fbxText.str();
  // A Z-up file (as 3ds Max and Blender write): up Z, front -Y, right X; units of metres.
  const std::pair<const char*, const char*> settings[] = {
      {"UpAxis", "2"},    {"UpAxisSign", "1"},    {"FrontAxis", "1"},        {"FrontAxisSign", "-1"},
      {"CoordAxis", "0"}, {"CoordAxisSign", "1"}, {"UnitScaleFactor", "100"}};
  for (const auto& [name, value] : settings) {
    const std::regex line("(P: \"" + std::string(name) + "\", \"[^\"]*\", \"[^\"]*\", \"[^\"]*\",)\\s*[-0-9.e+]+");
    ASSERT_TRUE(std::regex_search(fbx, line)) << name;
    fbx = std::regex_replace(fbx, line, std::string("$01") + value);  // $01: a digit may follow
  }
  std::ofstream(dir / "z_m.fbx") << fbx;
  expectBox(dir / "z_m.fbx", 1.0, "xzy");
}

// The files a mesh refers to pass the same input gate as the mesh: a glTF whose buffer is a
// FIFO or a link to /dev/zero is refused by the buffer's name instead of blocking or being
// read until memory runs out.
TEST(AssimpIo, FilesAMeshRefersToPassTheInputGate) {
  test::TempDir dir;
  Assimp::Exporter exporter;
  ASSERT_EQ(exporter.Export(boxScene().get(), "gltf2", (dir / "box.gltf").string()), AI_SUCCESS);
  std::filesystem::path buffer;
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    if (e.path().extension() == ".bin") buffer = e.path();
  ASSERT_FALSE(buffer.empty()) << "the exporter writes its buffer beside the .gltf";
  expectBox(dir / "box.gltf", 1.0);
  std::filesystem::remove(buffer);
  ASSERT_EQ(::mkfifo(buffer.c_str(), 0600), 0);
  test::expectErrorNaming([&] { readPolygonSoup(dir / "box.gltf"); }, buffer.filename().string(), "not a regular file");
  std::filesystem::remove(buffer);
  std::filesystem::create_symlink("/dev/zero", buffer);
  test::expectErrorNaming([&] { readPolygonSoup(dir / "box.gltf"); }, buffer.filename().string(), "not a regular file");
}

TEST(AssimpIo, RefusesWhatIsNotAMeshByName) {
  test::TempDir dir;
  std::ofstream(dir / "notes.gltf") << "{ not json";
  std::ofstream(dir / "points.stl") << "solid s\nendsolid s\n";
  test::expectErrorNaming([&] { readPolygonSoup(dir / "notes.gltf"); }, "notes.gltf", "its glTF JSON does not parse");
  test::expectErrorNaming([&] { readPolygonSoup(dir / "points.stl"); }, "points.stl", "");
  test::expectErrorNaming([&] { readPolygonSoup(dir / "missing.glb"); }, "missing.glb", "no such file");
}

// A file is read by an importer its extension names or refused: Assimp would otherwise hand
// a file none of them reads to any importer whose signature test it passes (a broken .gltf
// beginning "pmx" went to the PMX importer, which read past its buffer:
// fuzz/regressions/gltf). Here an STL that Assimp writes, named .dae, is refused, where by
// its signature Assimp would read it as STL; named .stl it is read.
TEST(AssimpIo, AFileIsReadByTheImporterItsExtensionNamesOrRefused) {
  test::TempDir dir;
  exportedBox(dir.path(), "stl", "box.stl");
  fs::copy_file(dir / "box.stl", dir / "box.dae");
  test::expectErrorNaming([&] { readPolygonSoup(dir / "box.dae"); }, "box.dae", "not a mesh Assimp can read");
  fs::copy_file(dir / "box.stl", dir / "box.mesh3");
  test::expectErrorNaming([&] { readPolygonSoup(dir / "box.mesh3"); }, "box.mesh3",
                          "not a mesh format shanshui reads by its extension '.mesh3'");
}

// A binary glTF's header and chunks must fit the file before Assimp reads it: it allocates
// and clears what the JSON chunk's length says (638 bytes claiming 4 GB took 4 GB:
// fuzz/regressions/glb).
TEST(AssimpIo, ABinaryGltfWhoseLengthsPassTheFileIsRefusedNamingThem) {
  test::TempDir dir;
  const std::string glb = exportedBox(dir.path(), "glb2", "box.glb");
  ASSERT_GT(glb.size(), 28u);
  auto with = [&](std::size_t at, std::uint32_t v, const char* name) {
    std::string bytes = glb;
    for (int k = 0; k < 4; ++k) bytes[at + k] = static_cast<char>((v >> (8 * k)) & 0xffu);
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  };
  const auto size = static_cast<std::uint32_t>(glb.size());
  test::expectErrorNaming(
      [&] { readPolygonSoup(with(8, size + 1, "long.glb")); }, "long.glb",
      "header says " + std::to_string(size + 1) + " bytes, but the file holds " + std::to_string(size));
  test::expectErrorNaming([&] { readPolygonSoup(with(12, 0xFFFD02CCu, "json.glb")); }, "json.glb",
                          "chunk 1 at byte 12 says 4294771404 bytes");
  std::ofstream(dir / "short.glb", std::ios::binary) << glb.substr(0, 16);
  test::expectErrorNaming([&] { readPolygonSoup(dir / "short.glb"); }, "short.glb", "shorter than its header");
}

// What Assimp 5.2's glTF reader misreads is refused before it reads the file, naming the
// primitive: one without positions (a line strip of none asked for 64 GB), an indexed line
// loop (with indices past its vertices it crashed), and JSON that is not UTF-8 (Assimp
// takes it, and such a file went on to crash it): fuzz/regressions/gltf and glb.
TEST(AssimpIo, AGltfAssimpWouldMisreadIsRefusedNamingWhy) {
  test::TempDir dir;
  const std::string json = exportedBox(dir.path(), "gltf2", "box.gltf");
  auto edited = [&](const std::string& from, const std::string& to, const char* name) {
    std::string text = json;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  };
  test::expectErrorNaming([&] { readPolygonSoup(edited("\"POSITION\"", "\"POSITIOM\"", "none.gltf")); }, "none.gltf",
                          "glTF mesh 0 primitive 0 has no POSITION attribute");
  test::expectErrorNaming([&] { readPolygonSoup(edited("\"mode\"", "\"mode\": 2, \"was\"", "loop.gltf")); },
                          "loop.gltf", "glTF mesh 0 primitive 0 is an indexed line loop");
  test::expectErrorNaming([&] { readPolygonSoup(edited("\"asset\"", "\"as\xffset\"", "bytes.gltf")); }, "bytes.gltf",
                          "its glTF JSON does not parse");
}

// Assimp reads in a child process: a file on which it dies (a COLLADA float array without
// its count: a null read in Assimp 5.2, fuzz/regressions/dae) is an error naming it, and
// the program goes on to read the next.
TEST(AssimpIo, AFileAssimpDiesOnIsAnErrorAndTheProgramGoesOn) {
  test::TempDir dir;
  const std::string dae = exportedBox(dir.path(), "collada", "box.dae");
  const std::string::size_type at = dae.find("float_array");
  ASSERT_NE(at, std::string::npos);
  const std::string::size_type count = dae.find("count=", at);
  ASSERT_NE(count, std::string::npos);
  std::ofstream(dir / "broken.dae", std::ios::binary) << dae.substr(0, count) + "cotnt=" + dae.substr(count + 6);
  test::expectErrorNaming([&] { readPolygonSoup(dir / "broken.dae"); }, "broken.dae", "Assimp died reading it");
  expectBox(dir / "box.dae", 1.0);
}

TEST(Creases, ACubeGetsSixFlatFacesAndASphereStaysSmooth) {
  Mesh cube = unitCube();
  const auto origin = splitAtCreases(cube, 40.0);
  EXPECT_EQ(cube.positions.size(), 24u) << "each corner once per side";
  ASSERT_EQ(origin.size(), 24u);
  for (std::size_t v = 0; v < origin.size(); ++v) EXPECT_EQ(cube.positions[v], unitCube().positions[origin[v]]);
  for (const glm::uvec3& t : cube.triangles) {
    const glm::dvec3 n = glm::normalize(
        glm::cross(cube.positions[t.y] - cube.positions[t.x], cube.positions[t.z] - cube.positions[t.x]));
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(glm::dvec3(cube.normals[t[k]]), n), 1.0 - 1e-6);
  }
  EXPECT_EQ(test::meshFacts(cube).boundary_edges, 24u) << "the 12 creases are cut, the 6 diagonals are not";

  Mesh smooth = unitCube();
  splitAtCreases(smooth, 180.0);
  EXPECT_EQ(smooth.positions.size(), 8u);
  EXPECT_LT(std::abs(smooth.normals[0].x), 0.9f) << "a corner's normal is between its three faces";

  Mesh sphere = icosphere(3);  // neighbouring faces meet at about 4 degrees
  const std::size_t n = sphere.positions.size();
  splitAtCreases(sphere, 40.0);
  EXPECT_EQ(sphere.positions.size(), n);
  for (std::size_t v = 0; v < n; ++v)
    EXPECT_GT(glm::dot(glm::dvec3(sphere.normals[v]), glm::normalize(sphere.positions[v])), 0.999);
}

}  // namespace
}  // namespace shanshui::mesh
