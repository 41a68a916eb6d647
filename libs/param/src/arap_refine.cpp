#include "arap_refine.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

namespace shanshui::param::detail {

namespace {

// A triangle in its own plane: corner coordinates x (x[0] at the origin, x[1] on the first
// axis) and each edge's cotangent weight, edge k joining corners k and k + 1 (mod 3), with
// the weight of the angle opposite it, halved (Σ w ‖Δu − R Δx‖² is then A ‖J − R‖²).
struct Flat {
  std::array<glm::dvec2, 3> x;
  std::array<double, 3> w;
};

// Conjugate-gradient iterations per read of the clock, and per local-global round at most
// (warm-started, a round needs far fewer than a solve from scratch).
constexpr int kChunk = 10, kRoundIterations = 60;

}  // namespace

RefineResult refineArap(const mesh::Mesh& m, std::vector<glm::dvec2>& uv,
                        std::chrono::steady_clock::time_point deadline, double tolerance,
                        const std::function<bool(const std::vector<glm::dvec2>&)>& enough) {
  using Clock = std::chrono::steady_clock;
  RefineResult result;
  const Eigen::Index n = static_cast<Eigen::Index>(m.positions.size());
  if (n < 3 || uv.size() != m.positions.size()) return result;
  std::vector<Flat> flat;
  std::vector<glm::uvec3> tris;
  flat.reserve(m.triangles.size());
  double area_sum = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    const glm::dvec3 a = m.positions[t.x], b = m.positions[t.y], c = m.positions[t.z];
    area_sum += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  const double tiny = 1e-12 * area_sum / std::max<std::size_t>(m.triangles.size(), 1);
  for (const glm::uvec3& t : m.triangles) {
    const std::array<glm::dvec3, 3> p{m.positions[t.x], m.positions[t.y], m.positions[t.z]};
    const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double twice_area = glm::length(glm::cross(e1, e2));
    if (!(0.5 * twice_area > tiny)) continue;  // no shape to keep
    Flat f;
    const double l1 = glm::length(e1);
    const double along = glm::dot(e2, e1) / l1;
    f.x = {glm::dvec2(0.0), glm::dvec2(l1, 0.0), glm::dvec2(along, twice_area / l1)};
    for (int k = 0; k < 3; ++k) {
      // Edge k (corners k, k+1) is opposite corner k+2.
      const glm::dvec3 a = p[k] - p[(k + 2) % 3], b = p[(k + 1) % 3] - p[(k + 2) % 3];
      f.w[k] = 0.5 * std::clamp(glm::dot(a, b) / twice_area, -1e4, 1e4);
    }
    flat.push_back(f);
    tris.push_back(t);
  }
  if (flat.empty()) return result;

  // The global step's matrix: the cotangent Laplacian (the Dirichlet energy's, positive
  // semi-definite), with vertex 0 tied softly to where it is.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(flat.size() * 12);
  double diagonal_sum = 0.0;
  for (std::size_t f = 0; f < flat.size(); ++f) {
    const std::array<Eigen::Index, 3> v{tris[f].x, tris[f].y, tris[f].z};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Index i = v[k], j = v[(k + 1) % 3];
      const double w = flat[f].w[k];
      entries.emplace_back(i, i, w);
      entries.emplace_back(j, j, w);
      entries.emplace_back(i, j, -w);
      entries.emplace_back(j, i, -w);
      diagonal_sum += 2 * w;
    }
  }
  const double anchor = 1e-6 * diagonal_sum / static_cast<double>(n);
  entries.emplace_back(0, 0, anchor);
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());
  Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Lower | Eigen::Upper> cg;
  cg.compute(L);
  cg.setTolerance(1e-9);
  cg.setMaxIterations(kChunk);

  Eigen::MatrixX2d u(n, 2), b(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) u.row(i) << uv[static_cast<std::size_t>(i)].x, uv[static_cast<std::size_t>(i)].y;
  const Eigen::RowVector2d pinned = u.row(0);
  std::vector<glm::dmat2> rotation(flat.size());
  // The local step: each triangle's nearest rotation to its map (the polar part of
  // Σ w Δu Δxᵀ, an angle in 2D), and the energy at that rotation.
  auto local = [&] {
    double energy = 0.0;
    for (std::size_t f = 0; f < flat.size(); ++f) {
      const std::array<Eigen::Index, 3> v{tris[f].x, tris[f].y, tris[f].z};
      double s00 = 0, s01 = 0, s10 = 0, s11 = 0;
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 du(u(v[k], 0) - u(v[(k + 1) % 3], 0), u(v[k], 1) - u(v[(k + 1) % 3], 1));
        const glm::dvec2 dx = flat[f].x[k] - flat[f].x[(k + 1) % 3];
        const double w = flat[f].w[k];
        s00 += w * du.x * dx.x, s01 += w * du.x * dx.y, s10 += w * du.y * dx.x, s11 += w * du.y * dx.y;
      }
      const double angle = std::atan2(s10 - s01, s00 + s11), c = std::cos(angle), s = std::sin(angle);
      rotation[f] = glm::dmat2(c, s, -s, c);  // columns
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 du(u(v[k], 0) - u(v[(k + 1) % 3], 0), u(v[k], 1) - u(v[(k + 1) % 3], 1));
        const glm::dvec2 r = du - rotation[f] * (flat[f].x[k] - flat[f].x[(k + 1) % 3]);
        energy += flat[f].w[k] * glm::dot(r, r);
      }
    }
    return energy;
  };
  auto copyOut = [&] {
    for (Eigen::Index i = 0; i < n; ++i) uv[static_cast<std::size_t>(i)] = {u(i, 0), u(i, 1)};
  };
  double energy = local();
  result.energy_start = result.energy_end = energy;
  while (Clock::now() < deadline) {
    ++result.iterations;
    b.setZero();
    for (std::size_t f = 0; f < flat.size(); ++f) {
      const std::array<Eigen::Index, 3> v{tris[f].x, tris[f].y, tris[f].z};
      for (int k = 0; k < 3; ++k) {
        const glm::dvec2 d = flat[f].w[k] * (rotation[f] * (flat[f].x[k] - flat[f].x[(k + 1) % 3]));
        b(v[k], 0) += d.x, b(v[k], 1) += d.y;
        b(v[(k + 1) % 3], 0) -= d.x, b(v[(k + 1) % 3], 1) -= d.y;
      }
    }
    b.row(0) += anchor * pinned;
    for (int done = 0; done < kRoundIterations && Clock::now() < deadline; done += kChunk) {
      u = cg.solveWithGuess(b, u);
      if (cg.info() == Eigen::Success) break;
    }
    const double before = energy;
    energy = local();
    result.energy_end = energy;
    if (!(before - energy > tolerance * before)) {
      result.converged = true;
      break;
    }
    if (enough) {
      copyOut();
      if (enough(uv)) {
        result.enough = true;
        return result;
      }
    }
  }
  copyOut();
  return result;
}

}  // namespace shanshui::param::detail
