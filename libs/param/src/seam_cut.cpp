#include "shanshui/param/seam_cut.h"

#include <algorithm>
#include <limits>
#include <map>
#include <queue>
#include <string>

#include "shanshui/core/error.h"

namespace shanshui::param {
namespace {

std::uint64_t directed(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

}  // namespace

SeamCut cutOpen(const mesh::Mesh& m, const std::string& what) {
  const std::size_t nv = m.positions.size();
  // Directed edge -> face; every edge must appear once in each direction (closed, oriented).
  std::map<std::uint64_t, std::uint32_t> faceOf;
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f) {
    const glm::uvec3 t = m.triangles[f];
    for (auto [a, b] : {std::pair{t.x, t.y}, std::pair{t.y, t.z}, std::pair{t.z, t.x}}) {
      if (!faceOf.emplace(directed(a, b), f).second) {
        throw makeError(what, ": edge (", a, ", ", b, ") is used twice in the same direction; repair the mesh first");
      }
    }
  }
  for (const auto& [key, f] : faceOf) {
    if (!faceOf.count(directed(static_cast<std::uint32_t>(key & 0xffffffffu), static_cast<std::uint32_t>(key >> 32)))) {
      throw makeError(what, ": not closed; only closed meshes are cut open");
    }
  }
  const long long euler = static_cast<long long>(nv) - static_cast<long long>(faceOf.size() / 2) +
                          static_cast<long long>(m.triangles.size());
  if (euler != 2) {
    throw makeError(what, ": closed mesh of genus ", (2 - euler) / 2,
                    "; only genus 0 (sphere-like) meshes can be cut open along one seam");
  }

  // Seam ends: the extreme vertices along the longest bounding-box axis.
  const mesh::Bounds b = mesh::bounds(m);
  const glm::dvec3 size = b.size();
  const int axis = size.x >= size.y && size.x >= size.z ? 0 : size.y >= size.z ? 1 : 2;
  std::uint32_t from = 0, to = 0;
  for (std::uint32_t v = 0; v < nv; ++v) {
    if (m.positions[v][axis] < m.positions[from][axis]) from = v;
    if (m.positions[v][axis] > m.positions[to][axis]) to = v;
  }
  if (from == to) throw makeError(what, ": degenerate closed mesh (no extent)");

  // Shortest edge path (Dijkstra on edge lengths).
  std::vector<std::vector<std::uint32_t>> neighbours(nv);
  for (const auto& [key, f] : faceOf) neighbours[key >> 32].push_back(static_cast<std::uint32_t>(key & 0xffffffffu));
  std::vector<double> dist(nv, std::numeric_limits<double>::infinity());
  std::vector<std::uint32_t> previous(nv, std::numeric_limits<std::uint32_t>::max());
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  dist[from] = 0.0;
  queue.push({0.0, from});
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    if (v == to) break;
    for (std::uint32_t w : neighbours[v]) {
      const double nd = d + glm::length(m.positions[w] - m.positions[v]);
      if (nd < dist[w]) {
        dist[w] = nd;
        previous[w] = v;
        queue.push({nd, w});
      }
    }
  }
  if (previous[to] == std::numeric_limits<std::uint32_t>::max()) {
    throw makeError(what, ": not connected; keep one component first");
  }
  SeamCut cut;
  for (std::uint32_t v = to; v != from; v = previous[v]) cut.seam.push_back(v);
  cut.seam.push_back(from);
  std::reverse(cut.seam.begin(), cut.seam.end());

  // Faces to the right of the seam (walking from `from` to `to`) take copies of the
  // interior seam vertices. Around seam vertex p with neighbours a (before) and c (after),
  // they are the fan from the face holding directed edge p->a, turning until the face
  // holding c->p.
  cut.mesh = m;
  // Attributes are one per vertex or none: a list of another length (a mesh assembled by
  // hand) is dropped rather than read past its end.
  const bool normals = m.normals.size() == m.positions.size(), uvs = m.uvs.size() == m.positions.size();
  if (!normals) cut.mesh.normals.clear();
  if (!uvs) cut.mesh.uvs.clear();
  for (std::size_t i = 1; i + 1 < cut.seam.size(); ++i) {
    const std::uint32_t a = cut.seam[i - 1], p = cut.seam[i], c = cut.seam[i + 1];
    const auto copy = static_cast<std::uint32_t>(cut.mesh.positions.size());
    cut.mesh.positions.push_back(m.positions[p]);
    if (normals) cut.mesh.normals.push_back(m.normals[p]);
    if (uvs) cut.mesh.uvs.push_back(m.uvs[p]);
    ++cut.duplicated;
    std::uint32_t f = faceOf.at(directed(p, a));
    for (std::size_t guard = 0; guard <= m.triangles.size(); ++guard) {
      glm::uvec3& t = cut.mesh.triangles[f];
      const glm::uvec3 orig = m.triangles[f];
      // Rotate so that p comes first: (p, x, y); the next face around p holds p->y.
      const std::uint32_t y = orig.x == p ? orig.z : orig.y == p ? orig.x : orig.y;
      for (int k = 0; k < 3; ++k) {
        if (t[k] == p) t[k] = copy;
      }
      if (y == c) break;
      f = faceOf.at(directed(p, y));
      SHANSHUI_CHECK_LT(guard, m.triangles.size());
    }
  }
  return cut;
}

}  // namespace shanshui::param
