#include "shanshui/mesh/mesh_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "shanshui/core/atomic_output.h"
#include "shanshui/core/error.h"
#include "shanshui/core/input.h"

namespace shanshui::mesh {
namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

void checkReadable(const fs::path& path) {
  checkInputFile(path, "a mesh", kMaxMeshBytes);
}

std::string firstLine(const std::string& s) {
  const auto end = s.find('\n');
  return s.substr(0, end);
}

// Shortest text that reads back to the same double.
void appendNumber(std::string& out, double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}

// One text row: `tag` (may be empty) and the numbers, separated by spaces.
template <typename... T>
void appendRow(std::string& out, const char* tag, T... values) {
  out += tag;
  bool first = *tag == '\0';
  ((out += first ? "" : " ", appendNumber(out, values), first = false), ...);
  out += '\n';
}

std::string objText(const Mesh& m) {
  std::string text = "# written by shanshui\n";
  text.reserve(m.positions.size() * 64 + m.triangles.size() * 32);
  for (const auto& p : m.positions) appendRow(text, "v", p.x, p.y, p.z);
  for (const auto& t : m.uvs) appendRow(text, "vt", t.x, t.y);
  for (const auto& n : m.normals) appendRow(text, "vn", n.x, n.y, n.z);
  const bool uv = !m.uvs.empty(), nrm = !m.normals.empty();
  for (const auto& tri : m.triangles) {
    text += 'f';
    for (int k = 0; k < 3; ++k) {
      const std::string i = std::to_string(tri[k] + 1);
      text += ' ';
      text += i;
      if (uv || nrm) text += '/';
      if (uv) text += i;
      if (nrm) {
        text += '/';
        text += i;
      }
    }
    text += '\n';
  }
  return text;
}

std::string offText(const Mesh& m) {
  std::string text = "OFF\n" + std::to_string(m.positions.size()) + " " + std::to_string(m.triangles.size()) + " 0\n";
  for (const auto& p : m.positions) appendRow(text, "", p.x, p.y, p.z);
  for (const auto& t : m.triangles) {
    text += "3 " + std::to_string(t.x) + " " + std::to_string(t.y) + " " + std::to_string(t.z) + "\n";
  }
  return text;
}

}  // namespace

std::string plyBytes(const Mesh& m);  // ply_io.cpp

// tinyobjloader turns an unparsable coordinate ("nan", "inf", "1.2.3") into 0, wraps an
// index too large for an int, and drops a face line with fewer than three corners (a file
// cut short), all without a word; vertex and face lines are checked here first so such a
// file is refused, not silently changed.
// Returns the corner count of every face line, in file order: tinyobjloader keeps the count
// in an unsigned char, so a face of 1000 corners would otherwise arrive as one of 232.
std::vector<std::size_t> checkObjLines(const fs::path& path) {
  std::vector<std::size_t> faceCorners;
  std::ifstream in(path);
  std::string line;
  for (long long number = 1; std::getline(in, line); ++number) {
    if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t')) continue;
    const char* p = line.data() + 2;
    const char* end = line.data() + line.size();
    if (line[0] == 'v') {
      for (int k = 0; k < 3; ++k) {
        while (p < end && (*p == ' ' || *p == '\t')) ++p;
        const char* start = p;
        while (p < end && *p != ' ' && *p != '\t' && *p != '\r') ++p;
        double value = 0.0;
        const auto [stop, ec] = std::from_chars(start, p, value);
        if (start == p || ec != std::errc() || stop != p || !std::isfinite(value)) {
          throw makeError(path.string(), ": line ", number, ": vertex coordinate '", std::string(start, p),
                          "' is not a finite number");
        }
      }
    } else if (line[0] == 'f') {
      int corners = 0;
      while (true) {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
        if (p >= end || *p == '#') break;
        const char* start = p;
        while (p < end && *p != ' ' && *p != '\t' && *p != '\r') ++p;
        // Each of v, v/vt, v//vn, v/vt/vn must be an integer that fits an int.
        for (const char* q = start; q < p;) {
          const char* r = q;
          while (r < p && *r != '/') ++r;
          if (r > q || q == start) {
            long long index = 0;
            const auto [stop, ec] = std::from_chars(q, r, index);
            if (q == r || ec != std::errc() || stop != r || index == 0 || index > 2147483647LL ||
                index < -2147483647LL) {
              throw makeError(path.string(), ": line ", number, ": face index '", std::string(q, r),
                              "' is not an index in [1, 2147483647] (or a negative relative one)");
            }
          }
          q = r < p ? r + 1 : r;
        }
        ++corners;
      }
      if (corners < 3) {
        throw makeError(path.string(), ": line ", number, ": face with ", corners,
                        " corner(s); expected at least 3 (file cut short?)");
      }
      faceCorners.push_back(static_cast<std::size_t>(corners));
    }
  }
  return faceCorners;
}

PolygonSoup readObj(const fs::path& path) {
  checkReadable(path);
  const std::vector<std::size_t> corners = checkObjLines(path);
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path.string(), config)) {
    throw makeError(path.string(), ": cannot read OBJ: ", firstLine(reader.Error()));
  }
  const tinyobj::attrib_t& a = reader.GetAttrib();
  PolygonSoup soup;
  bool anyUv = false, anyNormal = false;
  for (const auto& shape : reader.GetShapes()) {
    for (const auto& idx : shape.mesh.indices) {
      anyUv |= idx.texcoord_index >= 0;
      anyNormal |= idx.normal_index >= 0;
    }
  }
  // Vertex i of the file stays vertex i with the attributes of its first use; a later use
  // with other UV/normal indices gets a copy appended, so attributes stay per vertex.
  const std::size_t nv = a.vertices.size() / 3;
  for (std::size_t v = 0; v < nv; ++v) {
    soup.positions.emplace_back(a.vertices[3 * v], a.vertices[3 * v + 1], a.vertices[3 * v + 2]);
  }
  if (anyUv) soup.uvs.assign(nv, glm::vec2(0.0f));
  if (anyNormal) soup.normals.assign(nv, glm::vec3(0.0f));
  std::vector<std::pair<int, int>> firstUse(nv, {-2, -2});
  std::map<std::tuple<int, int, int>, std::uint32_t> copies;
  std::size_t faces = 0, indices = 0, nextFace = 0;
  for (const auto& shape : reader.GetShapes()) {
    faces += shape.mesh.num_face_vertices.size();
    indices += shape.mesh.indices.size();
  }
  std::size_t cornerSum = 0;
  for (std::size_t c : corners) cornerSum += c;
  if (faces != corners.size() || indices != cornerSum) {
    throw makeError(path.string(), ": cannot read OBJ: ", corners.size(), " face lines with ", cornerSum,
                    " corners, but the reader found ", faces, " faces with ", indices,
                    " corners (line continuations?)");
  }
  for (const auto& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t count = corners[nextFace++];
      std::vector<std::uint32_t> face;
      for (std::size_t k = 0; k < count; ++k) {
        const tinyobj::index_t idx = shape.mesh.indices[offset + k];
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= nv) {
          throw makeError(path.string(), ": face refers to vertex ", idx.vertex_index + 1, " but the file has ", nv,
                          " vertices");
        }
        const int vt = anyUv ? idx.texcoord_index : -1;
        const int vn = anyNormal ? idx.normal_index : -1;
        if (vt >= 0 && static_cast<std::size_t>(vt) * 2 + 1 >= a.texcoords.size()) {
          throw makeError(path.string(), ": face refers to texture coordinate ", vt + 1, " out of range");
        }
        if (vn >= 0 && static_cast<std::size_t>(vn) * 3 + 2 >= a.normals.size()) {
          throw makeError(path.string(), ": face refers to normal ", vn + 1, " out of range");
        }
        const auto v = static_cast<std::size_t>(idx.vertex_index);
        auto setAttributes = [&](std::size_t target) {
          if (anyUv && vt >= 0) soup.uvs[target] = {a.texcoords[2 * vt], a.texcoords[2 * vt + 1]};
          if (anyNormal && vn >= 0) {
            soup.normals[target] = {a.normals[3 * vn], a.normals[3 * vn + 1], a.normals[3 * vn + 2]};
          }
        };
        std::uint32_t id = static_cast<std::uint32_t>(v);
        if (firstUse[v].first == -2) {
          firstUse[v] = {vt, vn};
          setAttributes(v);
        } else if (firstUse[v] != std::make_pair(vt, vn)) {
          auto [it, inserted] =
              copies.try_emplace({idx.vertex_index, vt, vn}, static_cast<std::uint32_t>(soup.positions.size()));
          if (inserted) {
            soup.positions.push_back(soup.positions[v]);
            if (anyUv) soup.uvs.emplace_back(0.0f);
            if (anyNormal) soup.normals.emplace_back(0.0f);
            setAttributes(it->second);
          }
          id = it->second;
        }
        face.push_back(id);
      }
      offset += count;
      soup.faces.push_back(std::move(face));
    }
  }
  if (soup.faces.empty()) throw makeError(path.string(), ": OBJ has no faces");
  return soup;
}

PolygonSoup readOff(const fs::path& path) {
  checkReadable(path);
  std::ifstream in(path);
  if (!in) throw makeError(path.string(), ": cannot open");
  // Tokens with their line numbers, '#' comments removed. Records are read token by token
  // (OFF allows free layout) but anything left on a vertex or face line after the fields
  // we need (colours, COFF alpha) is skipped.
  struct Token {
    std::string text;
    int line;
  };
  std::vector<Token> tokens;
  std::string text;
  for (int lineNo = 1; std::getline(in, text); ++lineNo) {
    if (const auto hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream ls(text);
    std::string t;
    while (ls >> t) tokens.push_back({t, lineNo});
  }
  std::size_t pos = 0;
  auto fail = [&](const std::string& what) -> Error {
    const int line = pos < tokens.size() ? tokens[pos].line : (tokens.empty() ? 0 : tokens.back().line);
    return makeError(path.string(), ": line ", line, ": malformed OFF: ", what);
  };
  if (tokens.empty()) throw fail("no content");
  const std::string header = tokens[0].text;
  bool hasNormals = false, hasUv = false;
  if (header.size() >= 3 && header.substr(header.size() - 3) == "OFF") {
    const std::string prefix = header.substr(0, header.size() - 3);
    hasUv = prefix.find("ST") != std::string::npos;
    hasNormals = prefix.find('N') != std::string::npos;
    if (prefix.find('4') != std::string::npos || prefix.find('n') != std::string::npos) {
      throw fail("header '" + header + "': only 3D OFF is supported");
    }
    ++pos;
  }
  auto number = [&](const char* what) -> double {
    if (pos >= tokens.size()) throw fail(std::string("file ends early, expected ") + what + " (truncated?)");
    const std::string& t = tokens[pos].text;
    double v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) {
      throw fail(std::string("expected ") + what + ", found '" + t + "'");
    }
    ++pos;
    return v;
  };
  auto skipRestOfLine = [&](int line) {
    while (pos < tokens.size() && tokens[pos].line == line) ++pos;
  };
  const double nvD = number("vertex count"), nfD = number("face count");
  if (pos < tokens.size() && tokens[pos].line == tokens[pos - 1].line) number("edge count");
  if (nvD < 0 || nfD < 0 || nvD != std::floor(nvD) || nfD != std::floor(nfD) || nvD > 1e9 || nfD > 1e9) {
    throw fail("bad vertex/face counts");
  }
  const auto nv = static_cast<std::size_t>(nvD), nf = static_cast<std::size_t>(nfD);
  PolygonSoup soup;
  // Each vertex takes three tokens: a header that promises more than the file holds gets
  // no allocation for them (the read then stops at the first missing number).
  soup.positions.reserve(std::min(nv, tokens.size() / 3));
  for (std::size_t i = 0; i < nv; ++i) {
    const int line = pos < tokens.size() ? tokens[pos].line : 0;
    glm::dvec3 p;
    p.x = number("vertex x");
    p.y = number("vertex y");
    p.z = number("vertex z");
    soup.positions.push_back(p);
    if (hasNormals) {
      glm::vec3 n;
      for (int k = 0; k < 3; ++k) n[k] = static_cast<float>(number("vertex normal"));
      soup.normals.push_back(n);
    }
    if (hasUv) {
      glm::vec2 t;
      for (int k = 0; k < 2; ++k) t[k] = static_cast<float>(number("texture coordinate"));
      soup.uvs.push_back(t);
    }
    skipRestOfLine(line);
  }
  for (std::size_t f = 0; f < nf; ++f) {
    const int line = pos < tokens.size() ? tokens[pos].line : 0;
    const double k = number("face size");
    if (k < 0 || k != std::floor(k) || k > 1e6) throw fail("bad size of face " + std::to_string(f));
    if (k < 3) {
      throw makeError(path.string(), ": line ", line, ": face ", f, " has ", k, " corner(s); expected at least 3");
    }
    std::vector<std::uint32_t> face(static_cast<std::size_t>(k));
    for (auto& i : face) {
      const double v = number("vertex index");
      if (v < 0 || v != std::floor(v) || v >= static_cast<double>(nv)) {
        throw makeError(path.string(), ": line ", line, ": face ", f, " refers to vertex ", v, " but there are ", nv,
                        " vertices");
      }
      i = static_cast<std::uint32_t>(v);
    }
    soup.faces.push_back(std::move(face));
    skipRestOfLine(line);
  }
  if (soup.faces.empty()) throw makeError(path.string(), ": OFF has no faces");
  return soup;
}

PolygonSoup readPolygonSoup(const fs::path& path) {
  const std::string ext = lowerExtension(path);
  PolygonSoup soup;
  if (ext == ".obj")
    soup = readObj(path);
  else if (ext == ".off")
    soup = readOff(path);
  else if (ext == ".ply")
    soup = readPly(path);
  else
    soup = readAssimp(path);
  // Finite but huge coordinates overflow the geometry (a cross product of 1e308 is inf):
  // refused here with the value, rather than later as "NaN or infinite".
  for (std::size_t v = 0; v < soup.positions.size(); ++v) {
    for (int k = 0; k < 3; ++k) {
      const double c = soup.positions[v][k];
      if (std::isfinite(c) && std::abs(c) > kMaxCoordinate) {
        throw makeError(path.string(), ": vertex ", v + 1, " has coordinate ", c, ", outside +-", kMaxCoordinate,
                        "; scale the mesh down");
      }
    }
  }
  return soup;
}

std::string encodeMesh(const Mesh& mesh, const fs::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext != ".obj" && ext != ".off" && ext != ".ply") {
    throw makeError(path.string(), ": unknown mesh format '", ext, "' (expected .obj, .ply or .off)");
  }
  if (mesh.triangles.empty()) throw makeError(path.string(), ": refusing to write a mesh with no faces");
  if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
    throw makeError(path.string(), ": mesh has ", mesh.uvs.size(), " UVs for ", mesh.positions.size(), " vertices");
  }
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size()) {
    throw makeError(path.string(), ": mesh has ", mesh.normals.size(), " normals for ", mesh.positions.size(),
                    " vertices");
  }
  // Finite or refused: no file of ours holds a NaN or an infinity.
  auto refuse = [&](const char* what, std::size_t v, auto value) {
    std::ostringstream s;
    for (int k = 0; k < value.length(); ++k) s << (k ? " " : "") << value[k];
    throw makeError(path.string(), ": refusing to write a non-finite ", what, " (vertex ", v + 1, ": ", s.str(), ")");
  };
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!std::isfinite(mesh.positions[v].x + mesh.positions[v].y + mesh.positions[v].z)) {
      refuse("position", v, mesh.positions[v]);
    }
    if (!mesh.uvs.empty() && !std::isfinite(mesh.uvs[v].x + mesh.uvs[v].y)) refuse("UV", v, mesh.uvs[v]);
    if (!mesh.normals.empty() && !std::isfinite(mesh.normals[v].x + mesh.normals[v].y + mesh.normals[v].z)) {
      refuse("normal", v, mesh.normals[v]);
    }
  }
  if (ext == ".obj") return objText(mesh);
  if (ext == ".off") return offText(mesh);
  return plyBytes(mesh);
}

void writeMesh(const Mesh& mesh, const fs::path& path) {
  checkOutputPath(path);
  writeFileAtomically(path, encodeMesh(mesh, path));
}

}  // namespace shanshui::mesh
