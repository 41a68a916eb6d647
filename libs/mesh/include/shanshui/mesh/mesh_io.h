// Reading and writing meshes: OBJ (with UVs and normals), PLY (ASCII and binary), OFF; and
// reading every format Assimp knows (glTF 2.0, FBX, COLLADA, 3DS, STL, ...).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "shanshui/mesh/mesh.h"

namespace shanshui::mesh {

//! Reads the file as a polygon soup, choosing the format from the extension: .obj, .ply and
//! .off with shanshui's own readers, anything else through Assimp (readAssimp). OBJ vertices that carry different
//! UV/normal indices are split so attributes stay per vertex. Throws Error naming the file for unreadable, truncated or
//! malformed input and out-of-range indices. Non-finite coordinates are kept: repairMesh() removes them. Finite
//! coordinates beyond +-kMaxCoordinate are refused (they overflow normals and areas).
PolygonSoup readPolygonSoup(const std::filesystem::path& path);

constexpr double kMaxCoordinate = 1e15;

//! Largest mesh file read through Assimp (1 GiB), which reads a file whole.
constexpr std::uintmax_t kMaxMeshBytes = std::uintmax_t{1} << 30;

//! Writes the mesh (format from the extension) atomically: nothing replaces `path` on
//! failure. Positions keep full double precision. Throws Error for a mesh without faces.
void writeMesh(const Mesh& mesh, const std::filesystem::path& path);

//! The file's bytes for the format given by `path`'s extension (nothing is written).
std::string encodeMesh(const Mesh& mesh, const std::filesystem::path& path);

//! Readers by format, used by readPolygonSoup.
PolygonSoup readObj(const std::filesystem::path& path);
PolygonSoup readOff(const std::filesystem::path& path);
PolygonSoup readPly(const std::filesystem::path& path);
//! glTF 2.0 (.gltf/.glb), FBX, COLLADA, 3DS, STL and the other formats Assimp reads, in
//! metres with Y up (node transforms baked in; FBX's axes and unit scale, COLLADA's up
//! axis and unit applied; STL keeps its axes); the file's normals and first UV set when
//! every part has them. Conversions are listed in the soup's notes.
PolygonSoup readAssimp(const std::filesystem::path& path);

}  // namespace shanshui::mesh
