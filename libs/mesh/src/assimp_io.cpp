// Meshes in the formats artists export (glTF 2.0, FBX, COLLADA, 3DS, STL, and whatever else
// Assimp reads), as a polygon soup in metres with Y up, the OBJ/PLY convention the rest of
// shanshui assumes: node transforms are baked in, FBX's declared axes and unit scale are
// applied here, 3DS (always Z up) turned here, COLLADA's <up_axis> and <unit> by Assimp
// itself; glTF is Y-up metres by definition. STL declares neither: its axes are kept and
// the scene's `up` decides.
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <vector>

#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <nlohmann/json.hpp>

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

// A binary glTF's header and chunk lengths against the file's size, before Assimp reads it:
// Assimp allocates (and clears) what the JSON chunk's length says, so 638 bytes claiming a
// chunk of 4 GB took 4 GB. Files that do not start with the binary glTF magic pass. Returns
// the first chunk (the JSON) of a binary glTF, nothing for other files.
std::optional<std::string> checkGlbLengths(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[20] = {};
  in.read(reinterpret_cast<char*>(b), sizeof b);
  const auto got = static_cast<std::size_t>(in.gcount());
  auto le32 = [](const unsigned char* p) {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
  };
  auto u32 = [&](std::size_t at) { return le32(b + at); };
  if (got < 4 || u32(0) != 0x46546C67u) return std::nullopt;  // "glTF"
  const std::uintmax_t size = fs::file_size(path);
  if (got < sizeof b) throw makeError(path.string(), ": binary glTF of ", size, " bytes, shorter than its header");
  if (u32(8) > size)
    throw makeError(path.string(), ": binary glTF whose header says ", u32(8), " bytes, but the file holds ", size);
  // Chunks: a length, a type, then that many bytes; each must end inside the stated length.
  std::uintmax_t at = 12;
  std::string json;
  for (int chunk = 0; chunk < 2 && at + 8 <= u32(8); ++chunk) {
    unsigned char h[8] = {};
    in.seekg(static_cast<std::streamoff>(at));
    in.read(reinterpret_cast<char*>(h), sizeof h);
    const std::uint32_t length = le32(h);
    if (at + 8 + length > u32(8))
      throw makeError(path.string(), ": binary glTF chunk ", chunk + 1, " at byte ", at, " says ", length,
                      " bytes, past the ", u32(8), " the file's header gives");
    if (chunk == 0) {
      json.resize(length);
      in.read(json.data(), static_cast<std::streamsize>(length));
    }
    at += 8 + length;
  }
  return json;
}

// What Assimp 5.2's glTF 2.0 reader misreads, refused before it reads the file: a primitive
// without positions (a line strip of none made it ask for 64 GB) and an indexed line loop
// (one whose indices passed its vertices crashed it). shanshui draws triangles only. JSON
// that does not parse as the standard asks (UTF-8) is refused too: Assimp's parser takes
// invalid bytes in a key, and such a file went on to crash it.
void checkGltfPrimitives(const fs::path& path, const std::optional<std::string>& glb_json) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(glb_json ? *glb_json : readInputFile(path, "a mesh", kMaxMeshBytes));
  } catch (const nlohmann::json::exception& e) {
    std::string why = e.what();
    if (const auto colon = why.find(": "); colon != std::string::npos) why = why.substr(colon + 2);
    for (char& c : why)  // the bytes it quotes may be anything
      if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    throw makeError(path.string(), ": its glTF JSON does not parse (", why, ")");
  }
  if (!j.is_object() || !j.contains("meshes") || !j["meshes"].is_array()) return;
  const nlohmann::json& meshes = j["meshes"];
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (!meshes[m].is_object() || !meshes[m].contains("primitives") || !meshes[m]["primitives"].is_array()) continue;
    const nlohmann::json& primitives = meshes[m]["primitives"];
    for (std::size_t p = 0; p < primitives.size(); ++p) {
      const nlohmann::json& prim = primitives[p];
      if (!prim.is_object()) continue;
      const std::string which = "glTF mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      const bool positions =
          prim.contains("attributes") && prim["attributes"].is_object() && prim["attributes"].contains("POSITION");
      if (!positions)
        throw makeError(path.string(), ": ", which,
                        " has no POSITION attribute (nothing to draw, and Assimp 5.2 misreads it); remove it");
      const nlohmann::json* mode = prim.contains("mode") ? &prim["mode"] : nullptr;
      if (mode != nullptr && mode->is_number_integer() && mode->get<long long>() == 2 && prim.contains("indices"))
        throw makeError(path.string(), ": ", which,
                        " is an indexed line loop, which Assimp 5.2 misreads; shanshui draws triangles only: export "
                        "the model without its lines");
    }
  }
}

// The importers that claim the file's extension, the others removed from `importer`:
// when none of those reads the file, Assimp hands it to any importer whose signature test
// it passes, and a broken .gltf that began with "pmx" went to the PMX importer, which read
// past its buffer. An extension no importer claims is refused.
void keepImportersOf(Assimp::Importer& importer, const fs::path& path) {
  std::string name = path.filename().string();
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::size_t kept = 0;
  for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    std::set<std::string> extensions;
    reader->GetExtensionList(extensions);
    bool claims = false;
    for (const std::string& e : extensions)
      claims = claims || (name.size() > e.size() && name.ends_with(e) && name[name.size() - e.size() - 1] == '.');
    if (claims) {
      ++kept;
    } else if (importer.UnregisterLoader(reader) == AI_SUCCESS) {
      delete reader;  // no longer the importer's to delete
    }
  }
  if (kept == 0)
    throw makeError(path.string(), ": not a mesh format shanshui reads by its extension '", path.extension().string(),
                    "' (.obj, .ply, .off; .gltf, .glb, .fbx, .dae, .3ds, .stl and the other formats Assimp reads; a ",
                    "DEM becomes a mesh with shanshui-terrain)");
}

// The reading itself, in the child readAssimp starts.
PolygonSoup readAssimpHere(const fs::path& path) {
  Assimp::Importer importer;
  auto* io = new GatedIoSystem;  // the importer owns it
  importer.SetIOHandler(io);
  const std::optional<std::string> glb_json = checkGlbLengths(path);
  keepImportersOf(importer, path);
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (glb_json || ext == ".gltf") checkGltfPrimitives(path, glb_json);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene = importer.ReadFile(path.string(), aiProcess_SortByPType);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    if (!io->refused.empty()) throw makeError(path.string(), ": ", io->refused);
    throw makeError(path.string(), ": not a mesh Assimp can read (", importer.GetErrorString(), ")");
  }
  PolygonSoup soup;
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

// A soup and an error message as bytes through a pipe: sizes as 64-bit counts, then the
// values as they lie in memory (both ends are this program).
class Packer {
 public:
  explicit Packer(int fd) : fd_(fd) {}
  ~Packer() { flush(); }
  template <typename T>
  void values(const T* v, std::size_t n) {
    count(n);
    bytes(v, n * sizeof(T));
  }
  void count(std::uint64_t n) { bytes(&n, sizeof n); }
  void text(const std::string& t) { values(t.data(), t.size()); }
  void flush() {
    for (std::size_t at = 0; at < buffer_.size();) {
      const ssize_t n = ::write(fd_, buffer_.data() + at, buffer_.size() - at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) break;  // the parent has gone: nothing to tell
      at += static_cast<std::size_t>(n);
    }
    buffer_.clear();
  }

 private:
  void bytes(const void* p, std::size_t n) {
    if (n == 0) return;
    const char* c = static_cast<const char*>(p);
    buffer_.insert(buffer_.end(), c, c + n);
    if (buffer_.size() >= (std::size_t{1} << 16)) flush();
  }
  int fd_;
  std::vector<char> buffer_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::string& b) : b_(b) {}
  std::uint64_t count() {
    std::uint64_t n = 0;
    take(&n, sizeof n);
    return n;
  }
  template <typename T>
  std::vector<T> values() {
    const std::uint64_t n = count();
    if (n > (b_.size() - at_) / sizeof(T)) throw std::length_error("short");
    std::vector<T> v(n);
    take(v.data(), n * sizeof(T));
    return v;
  }
  std::string text() {
    const std::vector<char> c = values<char>();
    return {c.begin(), c.end()};
  }
  bool done() const { return at_ == b_.size(); }

 private:
  void take(void* p, std::size_t n) {
    if (n > b_.size() - at_) throw std::length_error("short");
    if (n == 0) return;  // an empty vector's data() may be null, which memcpy may not take
    std::memcpy(p, b_.data() + at_, n);
    at_ += n;
  }
  const std::string& b_;
  std::size_t at_ = 0;
};

}  // namespace

// In a child process: Assimp 5.2's FBX and COLLADA readers (and others) dereference null on
// malformed files the fuzzers found within seconds, which no check before it can foresee.
// The child reads the file and sends the soup (or the error) back through a pipe; a child
// that dies is reported as Assimp failing on the file, and the program goes on.
PolygonSoup readAssimp(const fs::path& path) {
  checkInputFile(path, "a mesh", kMaxMeshBytes);
  // Where no process can be started (a strict overcommit limit, a process table full), it is
  // read here, as before.
  int fds[2];
  if (::pipe(fds) != 0) return readAssimpHere(path);
  const pid_t child = ::fork();
  if (child < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return readAssimpHere(path);
  }
  if (child == 0) {
    ::close(fds[0]);
    int status = 0;
    {
      Packer out(fds[1]);
      try {
        const PolygonSoup soup = readAssimpHere(path);
        out.count(1);
        out.values(soup.positions.data(), soup.positions.size());
        out.values(soup.normals.data(), soup.normals.size());
        out.values(soup.uvs.data(), soup.uvs.size());
        out.count(soup.faces.size());
        for (const std::vector<std::uint32_t>& f : soup.faces) out.values(f.data(), f.size());
        out.count(soup.notes.size());
        for (const std::string& n : soup.notes) out.text(n);
      } catch (const std::exception& e) {
        out.count(0);
        out.text(e.what());
      } catch (...) {
        status = 3;
      }
    }
    ::_exit(status);  // no atexit handlers or stdio flushes of the parent's
  }
  ::close(fds[1]);
  std::string bytes;
  char chunk[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fds[0], chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    bytes.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  // Killed by a signal, or (under a sanitizer, which reports the fault and exits) by an exit
  // before the whole answer came.
  auto died = [&] {
    const std::string how = WIFSIGNALED(status) ? std::string(strsignal(WTERMSIG(status)))
                                                : "exit status " + std::to_string(WEXITSTATUS(status));
    return makeError(path.string(), ": Assimp died reading it (", how,
                     "): a malformed file, or one Assimp 5.2 cannot read; export it again, or as .obj or .ply");
  };
  if (WIFSIGNALED(status)) throw died();
  try {
    Unpacker in(bytes);
    if (in.count() == 0) throw Error(in.text());
    PolygonSoup soup;
    soup.positions = in.values<glm::dvec3>();
    soup.normals = in.values<glm::vec3>();
    soup.uvs = in.values<glm::vec2>();
    soup.faces.resize(in.count());
    for (std::vector<std::uint32_t>& f : soup.faces) f = in.values<std::uint32_t>();
    soup.notes.resize(in.count());
    for (std::string& n : soup.notes) n = in.text();
    if (!in.done()) throw std::length_error("long");
    return soup;
  } catch (const std::length_error&) {
    throw died();
  }
}

}  // namespace shanshui::mesh
