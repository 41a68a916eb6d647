// Reading and writing meshes: OBJ (with UVs and normals), PLY (ASCII and binary), OFF.
#pragma once

#include <filesystem>
#include <string>

#include "shanshui/mesh/mesh.h"

namespace shanshui::mesh {

//! Reads the file as a polygon soup, choosing the format from the extension (.obj, .ply,
//! .off). OBJ vertices that carry different UV/normal indices are split so attributes stay
//! per vertex. Throws Error naming the file for unreadable, truncated or malformed input
//! and out-of-range indices. Non-finite coordinates are kept: repairMesh() removes them.
//! Finite coordinates beyond +-kMaxCoordinate are refused (they overflow normals and areas).
PolygonSoup readPolygonSoup(const std::filesystem::path& path);

constexpr double kMaxCoordinate = 1e15;

//! Writes the mesh (format from the extension) atomically: nothing replaces `path` on
//! failure. Positions keep full double precision. Throws Error for a mesh without faces.
void writeMesh(const Mesh& mesh, const std::filesystem::path& path);

//! The file's bytes for the format given by `path`'s extension (nothing is written).
std::string encodeMesh(const Mesh& mesh, const std::filesystem::path& path);

//! Readers by format, used by readPolygonSoup.
PolygonSoup readObj(const std::filesystem::path& path);
PolygonSoup readOff(const std::filesystem::path& path);
PolygonSoup readPly(const std::filesystem::path& path);

}  // namespace shanshui::mesh
