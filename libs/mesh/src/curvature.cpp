#include "shanshui/mesh/curvature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>

#include "shanshui/core/error.h"

namespace shanshui::mesh {
namespace {

double cotangent(const glm::dvec3& a, const glm::dvec3& b) {
  const double s = glm::length(glm::cross(a, b));
  return s > 0.0 ? glm::dot(a, b) / s : 0.0;
}

}  // namespace

VertexCurvature estimateCurvature(const Mesh& m) {
  const std::size_t n = m.positions.size();
  std::vector<glm::dvec3> laplace(n, glm::dvec3(0.0));  // Σ (cot α + cot β)(x_j − x_i)
  std::vector<double> area(n, 0.0), angleSum(n, 0.0);
  std::vector<glm::dvec3> normal(n, glm::dvec3(0.0));
  // Border detection: an edge used once.
  std::vector<std::pair<std::uint64_t, int>> edges;
  edges.reserve(m.triangles.size() * 3);
  for (const glm::uvec3& t : m.triangles) {
    const std::uint32_t v[3] = {t.x, t.y, t.z};
    const glm::dvec3 p[3] = {m.positions[v[0]], m.positions[v[1]], m.positions[v[2]]};
    const glm::dvec3 faceNormal = glm::cross(p[1] - p[0], p[2] - p[0]);
    const double twiceArea = glm::length(faceNormal);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      edges.emplace_back((static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b), 1);
    }
    if (!(twiceArea > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      const int i = k, j = (k + 1) % 3, l = (k + 2) % 3;
      const glm::dvec3 eij = p[j] - p[i], eil = p[l] - p[i];
      // Angle at i; the edge j-l opposite to it gets cot(angle i).
      const double cotI = cotangent(eij, eil);
      laplace[v[j]] += cotI * (p[l] - p[j]);
      laplace[v[l]] += cotI * (p[j] - p[l]);
      angleSum[v[i]] += std::atan2(glm::length(glm::cross(eij, eil)), glm::dot(eij, eil));
      normal[v[i]] += faceNormal;
    }
    // Mixed area (Meyer et al., Fig. 4): Voronoi for non-obtuse triangles, else halves.
    const double faceArea = 0.5 * twiceArea;
    for (int k = 0; k < 3; ++k) {
      const int i = k, j = (k + 1) % 3, l = (k + 2) % 3;
      const glm::dvec3 eij = p[j] - p[i], eil = p[l] - p[i], ejl = p[l] - p[j];
      const bool obtuseI = glm::dot(eij, eil) < 0.0;
      const bool obtuseJ = glm::dot(-eij, ejl) < 0.0;
      const bool obtuseL = glm::dot(-eil, -ejl) < 0.0;
      if (obtuseI) {
        area[v[i]] += faceArea / 2.0;
      } else if (obtuseJ || obtuseL) {
        area[v[i]] += faceArea / 4.0;
      } else {
        area[v[i]] += (glm::dot(eij, eij) * cotangent(-ejl, -eil) + glm::dot(eil, eil) * cotangent(ejl, -eij)) / 8.0;
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  std::vector<bool> border(n, false);
  for (std::size_t e = 0; e < edges.size();) {
    std::size_t f = e;
    while (f < edges.size() && edges[f].first == edges[e].first) ++f;
    if (f - e == 1) {
      border[edges[e].first >> 32] = true;
      border[edges[e].first & 0xffffffffu] = true;
    }
    e = f;
  }

  VertexCurvature c;
  c.mean.assign(n, 0.0f);
  c.gaussian.assign(n, 0.0f);
  std::vector<bool> known(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (border[i] || !(area[i] > 0.0)) continue;
    // The cotangent Laplacian over the mixed area is the mean curvature normal 2H·n
    // (Meyer et al., Eq. 8); it points to the side the surface bends towards.
    const glm::dvec3 meanVector = laplace[i] / (2.0 * area[i]);
    const double sign = glm::dot(meanVector, normal[i]) < 0.0 ? 1.0 : -1.0;
    c.mean[i] = static_cast<float>(sign * glm::length(meanVector) / 2.0);
    c.gaussian[i] = static_cast<float>((2.0 * std::numbers::pi - angleSum[i]) / area[i]);
    known[i] = true;
  }
  // Border vertices (and isolated ones) copy their nearest known neighbour, breadth first.
  std::vector<std::vector<std::uint32_t>> neighbours(n);
  for (const glm::uvec3& t : m.triangles) {
    neighbours[t.x].push_back(t.y);
    neighbours[t.y].push_back(t.z);
    neighbours[t.z].push_back(t.x);
    neighbours[t.y].push_back(t.x);
    neighbours[t.z].push_back(t.y);
    neighbours[t.x].push_back(t.z);
  }
  std::queue<std::uint32_t> frontier;
  for (std::uint32_t i = 0; i < n; ++i)
    if (known[i]) frontier.push(i);
  while (!frontier.empty()) {
    const std::uint32_t i = frontier.front();
    frontier.pop();
    for (std::uint32_t j : neighbours[i]) {
      if (known[j]) continue;
      known[j] = true;
      c.mean[j] = c.mean[i];
      c.gaussian[j] = c.gaussian[i];
      frontier.push(j);
    }
  }
  c.k1.resize(n);
  c.k2.resize(n);
  c.magnitude.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double h = c.mean[i], root = std::sqrt(std::max(h * h - c.gaussian[i], 0.0));
    c.k1[i] = static_cast<float>(h + root);
    c.k2[i] = static_cast<float>(h - root);
    c.magnitude[i] = std::max(std::abs(c.k1[i]), std::abs(c.k2[i]));
  }
  return c;
}

namespace {

// Solves the n×n system A x = b (row-major, n ≤ 5) by Gaussian elimination with partial
// pivoting; false when it is singular.
bool solveSmall(double* a, double* b, int n) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(a[r * n + col]) > std::abs(a[pivot * n + col])) pivot = r;
    if (std::abs(a[pivot * n + col]) < 1e-12) return false;
    if (pivot != col) {
      for (int k = 0; k < n; ++k) std::swap(a[col * n + k], a[pivot * n + k]);
      std::swap(b[col], b[pivot]);
    }
    for (int r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] / a[col * n + col];
      for (int k = col; k < n; ++k) a[r * n + k] -= f * a[col * n + k];
      b[r] -= f * b[col];
    }
  }
  for (int r = n - 1; r >= 0; --r) {
    for (int k = r + 1; k < n; ++k) b[r] -= a[r * n + k] * b[k];
    b[r] /= a[r * n + r];
  }
  return true;
}

}  // namespace

VertexCurvature estimateCurvatureByFit(const Mesh& m) {
  VertexCurvature c = estimateCurvature(m);  // the fallback for vertices the fit cannot serve
  const std::size_t n = m.positions.size();
  // Vertex adjacency (CSR) and border vertices (an edge used by one triangle).
  std::vector<std::uint32_t> start(n + 1, 0), adj;
  {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(m.triangles.size() * 6);
    for (const glm::uvec3& t : m.triangles) {
      for (int k = 0; k < 3; ++k) {
        edges.emplace_back(t[k], t[(k + 1) % 3]);
        edges.emplace_back(t[(k + 1) % 3], t[k]);
      }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& e : edges) ++start[e.first + 1];
    for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
    adj.resize(edges.size());
    for (std::size_t i = 0; i < edges.size(); ++i) adj[i] = edges[i].second;
  }
  std::vector<bool> border(n, false);
  {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> half;
    for (const glm::uvec3& t : m.triangles)
      for (int k = 0; k < 3; ++k) half.emplace_back(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
    std::sort(half.begin(), half.end());
    for (std::size_t i = 0; i < half.size(); ++i) {
      const bool single = (i == 0 || half[i - 1] != half[i]) && (i + 1 == half.size() || half[i + 1] != half[i]);
      if (single) border[half[i].first] = border[half[i].second] = true;
    }
  }
  const std::vector<glm::vec3> normals = vertexNormals(m);
  std::vector<std::uint32_t> stamp(n, UINT32_MAX), ring;
  for (std::uint32_t i = 0; i < n; ++i) {
    if (border[i]) continue;
    ring.clear();
    stamp[i] = i;
    for (std::uint32_t a = start[i]; a < start[i + 1]; ++a) {
      const std::uint32_t j = adj[a];
      if (stamp[j] != i) stamp[j] = i, ring.push_back(j);
    }
    const std::size_t first_ring = ring.size();
    for (std::size_t r = 0; r < first_ring; ++r)
      for (std::uint32_t a = start[ring[r]]; a < start[ring[r] + 1]; ++a) {
        const std::uint32_t j = adj[a];
        if (stamp[j] != i) stamp[j] = i, ring.push_back(j);
      }
    if (ring.size() < 6) continue;
    // Tangent frame, coordinates scaled by the mean neighbour distance for conditioning.
    const glm::dvec3 nz = glm::normalize(glm::dvec3(normals[i]));
    const glm::dvec3 helper = std::abs(nz.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 tx = glm::normalize(glm::cross(helper, nz)), ty = glm::cross(nz, tx);
    double h = 0;
    for (std::uint32_t j : ring) h += glm::length(m.positions[j] - m.positions[i]);
    h /= static_cast<double>(ring.size());
    if (!(h > 0)) continue;
    double ata[25] = {}, atb[5] = {};
    for (std::uint32_t j : ring) {
      const glm::dvec3 d = (m.positions[j] - m.positions[i]) / h;
      const double x = glm::dot(d, tx), y = glm::dot(d, ty), z = -glm::dot(d, nz);  // + bends away from n
      const double row[5] = {x * x, x * y, y * y, x, y};
      for (int r = 0; r < 5; ++r) {
        for (int k = 0; k < 5; ++k) ata[r * 5 + k] += row[r] * row[k];
        atb[r] += row[r] * z;
      }
    }
    if (!solveSmall(ata, atb, 5)) continue;
    // Shape operator of the graph z = f(x, y) at the origin: I⁻¹ II.
    const double fx = atb[3], fy = atb[4], fxx = 2 * atb[0], fxy = atb[1], fyy = 2 * atb[2];
    const double w = std::sqrt(1 + fx * fx + fy * fy);
    const double e = 1 + fx * fx, f = fx * fy, g = 1 + fy * fy;
    const double l = fxx / w, mm = fxy / w, nn = fyy / w;
    const double det = e * g - f * f;
    const double s11 = (g * l - f * mm) / det, s12 = (g * mm - f * nn) / det;
    const double s21 = (e * mm - f * l) / det, s22 = (e * nn - f * mm) / det;
    const double mean = 0.5 * (s11 + s22), gauss = s11 * s22 - s12 * s21;
    const double root = std::sqrt(std::max(mean * mean - gauss, 0.0));
    // Back to mesh units (z was measured against the normal: estimateCurvature's sign).
    c.mean[i] = static_cast<float>(mean / h);
    c.gaussian[i] = static_cast<float>(gauss / (h * h));
    c.k1[i] = static_cast<float>((mean + root) / h);
    c.k2[i] = static_cast<float>((mean - root) / h);
    c.magnitude[i] = std::max(std::abs(c.k1[i]), std::abs(c.k2[i]));
  }
  return c;
}

double curvatureFeatureSize(const Mesh& m, const VertexCurvature& c, double percentile) {
  if (!(percentile > 0.0 && percentile < 100.0)) {
    throw makeError("curvature feature size: percentile ", percentile, "; expected (0, 100)");
  }
  SHANSHUI_CHECK_EQ(c.magnitude.size(), m.positions.size());
  // Area weight per vertex: a third of the incident faces' areas.
  std::vector<std::pair<float, double>> weighted(m.positions.size());
  for (std::size_t i = 0; i < weighted.size(); ++i) weighted[i] = {c.magnitude[i], 0.0};
  double total = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const double a =
        glm::length(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x])) / 6.0;
    weighted[t.x].second += a;
    weighted[t.y].second += a;
    weighted[t.z].second += a;
    total += 3.0 * a;
  }
  std::sort(weighted.begin(), weighted.end());
  double sum = 0.0;
  for (const auto& [k, w] : weighted) {
    sum += w;
    if (sum >= percentile / 100.0 * total) return k > 0.0f ? 1.0 / k : 0.0;
  }
  return 0.0;
}

void smoothOverOneRing(const Mesh& m, std::vector<float>& field, int iterations) {
  SHANSHUI_CHECK_EQ(field.size(), m.positions.size());
  if (iterations <= 0) return;
  // Edge neighbours in compressed rows; an edge shared by two faces is listed once.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(6 * m.triangles.size());
  for (const glm::uvec3& t : m.triangles) {
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t a = t[e], b = t[(e + 1) % 3];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::uint32_t> start(m.positions.size() + 1, 0);
  for (const auto& [a, b] : edges) {
    ++start[a + 1];
    ++start[b + 1];
  }
  for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  std::vector<std::uint32_t> neighbours(start.back()), fill(start.begin(), start.end() - 1);
  for (const auto& [a, b] : edges) {
    neighbours[fill[a]++] = b;
    neighbours[fill[b]++] = a;
  }
  std::vector<float> out(field.size());
  for (int it = 0; it < iterations; ++it) {
    for (std::size_t v = 0; v < field.size(); ++v) {
      double sum = field[v];
      for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) sum += field[neighbours[k]];
      out[v] = static_cast<float>(sum / (1.0 + (start[v + 1] - start[v])));
    }
    field.swap(out);
  }
}

}  // namespace shanshui::mesh
