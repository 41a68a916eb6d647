// PLY reader (ASCII, binary little- and big-endian) and binary writer. Written by hand:
// Debian bookworm packages no maintained PLY library, and CGAL's reader would pull CGAL
// headers into every mesh-reading translation unit.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "shanshui/core/error.h"
#include "shanshui/core/input.h"
#include "shanshui/mesh/mesh_io.h"

namespace shanshui::mesh {
namespace fs = std::filesystem;

namespace {

enum class Scalar { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parseScalar(const std::string& t, Scalar& s) {
  static const std::pair<const char*, Scalar> names[] = {
      {"char", Scalar::Int8},      {"int8", Scalar::Int8},       {"uchar", Scalar::UInt8},
      {"uint8", Scalar::UInt8},    {"short", Scalar::Int16},     {"int16", Scalar::Int16},
      {"ushort", Scalar::UInt16},  {"uint16", Scalar::UInt16},   {"int", Scalar::Int32},
      {"int32", Scalar::Int32},    {"uint", Scalar::UInt32},     {"uint32", Scalar::UInt32},
      {"float", Scalar::Float32},  {"float32", Scalar::Float32}, {"double", Scalar::Float64},
      {"float64", Scalar::Float64}};
  for (const auto& [name, value] : names) {
    if (t == name) {
      s = value;
      return true;
    }
  }
  return false;
}

int scalarSize(Scalar s) {
  switch (s) {
    case Scalar::Int8:
    case Scalar::UInt8:
      return 1;
    case Scalar::Int16:
    case Scalar::UInt16:
      return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32:
      return 4;
    case Scalar::Float64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;
  bool isList = false;
  Scalar countType = Scalar::UInt8;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

// Reads scalars from the body in whichever encoding the header declared.
class BodyReader {
 public:
  BodyReader(std::istream& in, Format format, const fs::path& path) : in_(in), format_(format), path_(path) {}

  double read(Scalar s) {
    if (format_ == Format::Ascii) {
      std::string t;
      if (!(in_ >> t)) throw truncated();
      try {
        std::size_t used = 0;
        const double v = std::stod(t, &used);
        if (used != t.size()) throw std::invalid_argument(t);
        return v;
      } catch (const std::exception&) {
        throw makeError(path_.string(), ": malformed PLY: expected a number, found '", t, "'");
      }
    }
    unsigned char b[8];
    const int n = scalarSize(s);
    if (!in_.read(reinterpret_cast<char*>(b), n)) throw truncated();
    const bool swap = (format_ == Format::BinaryBE) != (std::endian::native == std::endian::big);
    if (swap) std::reverse(b, b + n);
    switch (s) {
      case Scalar::Int8: {
        std::int8_t v;
        std::memcpy(&v, b, 1);
        return v;
      }
      case Scalar::UInt8:
        return b[0];
      case Scalar::Int16: {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Scalar::UInt16: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Scalar::Int32: {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Scalar::UInt32: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Scalar::Float32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Scalar::Float64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
    return 0;
  }

 private:
  Error truncated() const { return makeError(path_.string(), ": PLY body ends early (truncated file?)"); }
  std::istream& in_;
  Format format_;
  const fs::path& path_;
};

}  // namespace

PolygonSoup readPly(const fs::path& path) {
  checkInputFile(path, "a mesh", kMaxMeshBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw makeError(path.string(), ": cannot open");
  auto bad = [&](const std::string& what) { return makeError(path.string(), ": malformed PLY: ", what); };

  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) throw bad("missing 'ply' magic line");
  Format format = Format::Ascii;
  bool sawFormat = false;
  std::vector<Element> elements;
  while (true) {
    if (!std::getline(in, line)) throw bad("header has no end_header");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "end_header") break;
    if (key == "comment" || key == "obj_info" || key.empty()) continue;
    if (key == "format") {
      std::string f;
      ls >> f;
      if (f == "ascii")
        format = Format::Ascii;
      else if (f == "binary_little_endian")
        format = Format::BinaryLE;
      else if (f == "binary_big_endian")
        format = Format::BinaryBE;
      else
        throw bad("unknown format '" + f + "'");
      sawFormat = true;
    } else if (key == "element") {
      Element e;
      double count = -1;
      ls >> e.name >> count;
      if (!ls || count < 0 || count > 1e10) throw bad("bad element line '" + line + "'");
      e.count = static_cast<std::size_t>(count);
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) throw bad("property before any element");
      Property p;
      std::string type;
      ls >> type;
      if (type == "list") {
        std::string countType, itemType;
        ls >> countType >> itemType >> p.name;
        if (!parseScalar(countType, p.countType) || !parseScalar(itemType, p.type)) {
          throw bad("bad list property '" + line + "'");
        }
        p.isList = true;
      } else {
        ls >> p.name;
        if (!parseScalar(type, p.type)) throw bad("unknown property type '" + type + "'");
      }
      elements.back().properties.push_back(p);
    } else {
      throw bad("unknown header line '" + line + "'");
    }
  }
  if (!sawFormat) throw bad("header has no format line");

  PolygonSoup soup;
  BodyReader body(in, format, path);
  for (const Element& e : elements) {
    // An element without properties takes no bytes however many it says it has (a header
    // counting three billion of them made this loop run for minutes): nothing to read.
    if (e.properties.empty()) continue;
    const bool isVertex = e.name == "vertex";
    const bool isFace = e.name == "face";
    int ix = -1, iy = -1, iz = -1, inx = -1, iny = -1, inz = -1, iu = -1, iv = -1, iface = -1;
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      const std::string& n = e.properties[k].name;
      if (n == "x")
        ix = k;
      else if (n == "y")
        iy = k;
      else if (n == "z")
        iz = k;
      else if (n == "nx")
        inx = k;
      else if (n == "ny")
        iny = k;
      else if (n == "nz")
        inz = k;
      else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s")
        iu = k;
      else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t")
        iv = k;
      else if (n == "vertex_indices" || n == "vertex_index")
        iface = k;
    }
    if (isVertex && (ix < 0 || iy < 0 || iz < 0)) throw bad("vertex element lacks x, y or z");
    if (isFace && iface < 0) throw bad("face element lacks vertex_indices");
    const bool normals = isVertex && inx >= 0 && iny >= 0 && inz >= 0;
    const bool uvs = isVertex && iu >= 0 && iv >= 0;
    std::vector<double> values(e.properties.size());
    for (std::size_t i = 0; i < e.count; ++i) {
      std::vector<std::uint32_t> face;
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const Property& p = e.properties[k];
        if (!p.isList) {
          values[k] = body.read(p.type);
          continue;
        }
        const double n = body.read(p.countType);
        if (!(n >= 0 && n <= 1e6) || n != std::floor(n)) throw bad("bad list length " + std::to_string(n));
        for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) {
          const double idx = body.read(p.type);
          if (isFace && static_cast<int>(k) == iface) {
            // A text file may hold any number here: only a whole one a vertex can have.
            if (!(idx >= 0 && idx <= 4294967295.0) || idx != std::floor(idx)) {
              throw bad("face " + std::to_string(i) + ": vertex index " + std::to_string(idx) +
                        " is not a whole number from 0 to 4294967295");
            }
            face.push_back(static_cast<std::uint32_t>(idx));
          }
        }
      }
      if (isVertex) {
        soup.positions.emplace_back(values[ix], values[iy], values[iz]);
        if (normals) soup.normals.emplace_back(values[inx], values[iny], values[inz]);
        if (uvs) soup.uvs.emplace_back(values[iu], values[iv]);
      } else if (isFace) {
        if (face.size() < 3) {
          throw bad("face " + std::to_string(soup.faces.size()) + " has " + std::to_string(face.size()) +
                    " corner(s); expected at least 3");
        }
        soup.faces.push_back(std::move(face));
      }
    }
  }
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    for (std::uint32_t i : soup.faces[f]) {
      if (i >= soup.positions.size()) {
        throw makeError(path.string(), ": face ", f, " refers to vertex ", i, " but there are only ",
                        soup.positions.size(), " vertices");
      }
    }
  }
  if (soup.faces.empty()) throw makeError(path.string(), ": PLY has no faces");
  return soup;
}

std::string plyBytes(const Mesh& m) {
  std::ostringstream out(std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\ncomment written by shanshui\n"
      << "element vertex " << m.positions.size() << "\n"
      << "property double x\nproperty double y\nproperty double z\n";
  const bool normals = !m.normals.empty(), uvs = !m.uvs.empty();
  if (normals) out << "property float nx\nproperty float ny\nproperty float nz\n";
  if (uvs) out << "property float u\nproperty float v\n";
  out << "element face " << m.triangles.size() << "\n"
      << "property list uchar uint vertex_indices\nend_header\n";
  auto put = [&](auto v) {
    if constexpr (std::endian::native == std::endian::big) {
      char b[sizeof v];
      std::memcpy(b, &v, sizeof v);
      std::reverse(b, b + sizeof v);
      out.write(b, sizeof v);
    } else {
      out.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
  };
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) put(m.positions[i][k]);
    if (normals)
      for (int k = 0; k < 3; ++k) put(m.normals[i][k]);
    if (uvs)
      for (int k = 0; k < 2; ++k) put(m.uvs[i][k]);
  }
  for (const glm::uvec3& t : m.triangles) {
    put(static_cast<std::uint8_t>(3));
    for (int k = 0; k < 3; ++k) put(static_cast<std::uint32_t>(t[k]));
  }
  return std::move(out).str();
}

}  // namespace shanshui::mesh
