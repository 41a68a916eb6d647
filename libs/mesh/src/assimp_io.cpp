// Meshes in the formats artists export (glTF 2.0, FBX, COLLADA, 3DS, STL, and whatever else
// Assimp reads), as a polygon soup in metres with Y up, the OBJ/PLY convention the rest of
// shanshui assumes: node transforms are baked in, FBX's declared axes and unit scale are
// applied here, 3DS (always Z up) turned here, COLLADA's <up_axis> and <unit> by Assimp
// itself; glTF is Y-up metres by definition. STL declares neither: its axes are kept and
// the scene's `up` decides.
#include <cmath>

#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/mesh/mesh_io.h"

namespace shanshui::mesh {
namespace fs = std::filesystem;
namespace {

template <typename T>
bool metadata(const aiScene* scene, const char* key, T& value) {
  return scene->mMetaData != nullptr && scene->mMetaData->Get(key, value);
}

// FBX says which file axes are up, front and right (each with a sign) and how many
// centimetres one unit is. Turns the root so that up is +Y and scales units to metres.
void applyFbxAxesAndUnits(const aiScene* scene, PolygonSoup& soup) {
  int up = 1, upSign = 1, front = 2, frontSign = 1, coord = 0, coordSign = 1;
  const bool axes = metadata(scene, "UpAxis", up) && metadata(scene, "UpAxisSign", upSign) &&
                    metadata(scene, "FrontAxis", front) && metadata(scene, "FrontAxisSign", frontSign) &&
                    metadata(scene, "CoordAxis", coord) && metadata(scene, "CoordAxisSign", coordSign);
  double unitCm = 1.0;
  float unitF = 1.0f;
  if (metadata(scene, "UnitScaleFactor", unitCm)) {
  } else if (metadata(scene, "UnitScaleFactor", unitF)) {
    unitCm = unitF;
  }
  aiMatrix4x4 turn;
  const bool valid = axes && up >= 0 && up < 3 && front >= 0 && front < 3 && coord >= 0 && coord < 3 && up != front &&
                     up != coord && front != coord;
  if (valid && !(up == 1 && upSign == 1 && coord == 0 && coordSign == 1)) {
    aiVector3D r, u, f;
    r[coord] = static_cast<ai_real>(coordSign);
    u[up] = static_cast<ai_real>(upSign);
    f[front] = static_cast<ai_real>(frontSign);
    // Rows: the file's right, up and front become x, y and z.
    turn = aiMatrix4x4(r.x, r.y, r.z, 0, u.x, u.y, u.z, 0, f.x, f.y, f.z, 0, 0, 0, 0, 1);
    if (turn.Determinant() < 0) {  // a left-handed declaration: mirror front to keep the winding
      turn.c1 = -turn.c1, turn.c2 = -turn.c2, turn.c3 = -turn.c3;
    }
    soup.notes.push_back("FBX axes (up " + std::string(1, "XYZ"[up]) + (upSign > 0 ? "+" : "-") + ") turned to Y up");
  }
  if (std::isfinite(unitCm) && unitCm > 0 && unitCm != 100.0) {
    const auto s = static_cast<ai_real>(unitCm / 100.0);
    aiMatrix4x4 scale;
    aiMatrix4x4::Scaling(aiVector3D(s, s, s), scale);
    turn = scale * turn;
    soup.notes.push_back("FBX units of " + std::to_string(unitCm) + " cm converted to metres");
  }
  scene->mRootNode->mTransformation = turn * scene->mRootNode->mTransformation;
}

// Assimp opens the files a mesh refers to itself (a glTF's .bin buffers, an OBJ's .mtl):
// each goes through the input gate too, so a FIFO or /dev/zero named there cannot hang or
// exhaust memory. A refused file is remembered to name it in the error.
class GatedIoSystem : public Assimp::DefaultIOSystem {
 public:
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    std::error_code missing;  // a file that is not there is Assimp's to report
    if (mode != nullptr && mode[0] == 'r' && fs::exists(file, missing)) {
      try {
        checkInputFile(file, "a file the mesh refers to", kMaxMeshBytes);
      } catch (const Error& e) {
        if (refused.empty()) refused = e.what();
        return nullptr;
      }
    }
    return DefaultIOSystem::Open(file, mode);
  }
  // The default opens the file to see whether it is there, which blocks on a FIFO.
  bool Exists(const char* file) const override {
    std::error_code ec;
    return fs::exists(file, ec);
  }
  std::string refused;
};

}  // namespace

PolygonSoup readAssimp(const fs::path& path) {
  checkInputFile(path, "a mesh", kMaxMeshBytes);
  Assimp::Importer importer;
  auto* io = new GatedIoSystem;  // the importer owns it
  importer.SetIOHandler(io);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    if (!io->refused.empty()) throw makeError(path.string(), ": ", io->refused);
    throw makeError(path.string(), ": not a mesh Assimp can read (", importer.GetErrorString(), ")");
  }
  PolygonSoup soup;
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".fbx") applyFbxAxesAndUnits(scene, soup);
  if (ext == ".3ds") {  // 3ds Max's files are Z up, and Assimp keeps them so
    scene->mRootNode->mTransformation =
        aiMatrix4x4(1, 0, 0, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1) * scene->mRootNode->mTransformation;
    soup.notes.push_back("3DS (Z up) turned to Y up");
  }
  // Node transforms (and what was applied above) baked into the vertices, one mesh per
  // material merged.
  scene = importer.ApplyPostProcessing(aiProcess_PreTransformVertices);
  if (scene == nullptr) throw makeError(path.string(), ": ", importer.GetErrorString());
  bool normals = true, uvs = true;
  std::size_t faces = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && !(mesh->mPrimitiveTypes & aiPrimitiveType_POLYGON))
      continue;
    normals = normals && mesh->HasNormals();
    uvs = uvs && mesh->HasTextureCoords(0);
    faces += mesh->mNumFaces;
  }
  if (faces == 0) throw makeError(path.string(), ": has no faces (points or lines only, or empty)");
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) && !(mesh->mPrimitiveTypes & aiPrimitiveType_POLYGON))
      continue;
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      soup.positions.emplace_back(p.x, p.y, p.z);
      if (normals) soup.normals.emplace_back(mesh->mNormals[v].x, mesh->mNormals[v].y, mesh->mNormals[v].z);
      if (uvs) soup.uvs.emplace_back(mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y);
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices < 3) continue;
      std::vector<std::uint32_t> poly(face.mNumIndices);
      for (unsigned k = 0; k < face.mNumIndices; ++k) poly[k] = base + face.mIndices[k];
      soup.faces.push_back(std::move(poly));
    }
  }
  return soup;
}

}  // namespace shanshui::mesh
