#include "shanshui/strokes/chains.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>

#include "shanshui/core/error.h"

namespace shanshui::strokes {
namespace {

constexpr double kSamePoint = 1e-6;  // pixels: pieces of one edge, or of edges that meet

double turn(glm::dvec2 from, glm::dvec2 to) {
  const double lf = glm::length(from), lt = glm::length(to);
  if (lf == 0.0 || lt == 0.0) return 0.0;
  return std::acos(std::clamp(glm::dot(from, to) / (lf * lt), -1.0, 1.0));
}

// Grid of piece ends for the neighbour search.
struct EndGrid {
  double cell;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells;  // key -> end ids (2 per piece)
  static std::int64_t key(std::int64_t x, std::int64_t y) { return (x << 32) ^ (y & 0xffffffff); }
  std::int64_t at(double v) const { return static_cast<std::int64_t>(std::floor(v / cell)); }
  void add(glm::dvec2 p, std::uint32_t id) { cells[key(at(p.x), at(p.y))].push_back(id); }
};

}  // namespace

std::vector<Chain> linkSegments(const std::vector<ScreenSegment>& segs, const LinkOptions& o) {
  if (!(o.max_turn_deg >= 0.0 && o.max_turn_deg <= 180.0)) {
    throw makeError("link turn ", o.max_turn_deg, " degrees; expected [0, 180]");
  }
  if (!(o.max_gap_px >= 0.0 && o.max_gap_px <= 1000.0))
    throw makeError("link gap ", o.max_gap_px, " px; expected [0, 1000]");
  const double maxTurn = o.max_turn_deg * M_PI / 180.0;
  EndGrid grid{std::max(o.max_gap_px, 1.0), {}};
  auto endPoint = [&](std::uint32_t id) { return id % 2 == 0 ? segs[id / 2].a : segs[id / 2].b; };
  for (std::uint32_t i = 0; i < segs.size(); ++i) {
    grid.add(segs[i].a, 2 * i);
    grid.add(segs[i].b, 2 * i + 1);
  }
  std::vector<bool> used(segs.size(), false);
  std::vector<std::uint32_t> order(segs.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) {
    return glm::length(segs[x].b - segs[x].a) > glm::length(segs[y].b - segs[y].a);
  });
  // The unused end closest to `tip` (moving along `dir`) within the gap and the turn; the
  // piece is then walked from that end to its other one.
  auto nextPiece = [&](glm::dvec2 tip, glm::dvec2 dir, std::uint32_t* endId) {
    double best = std::numeric_limits<double>::infinity();
    bool found = false;
    const std::int64_t cx = grid.at(tip.x), cy = grid.at(tip.y);
    for (std::int64_t y = cy - 1; y <= cy + 1; ++y)
      for (std::int64_t x = cx - 1; x <= cx + 1; ++x) {
        const auto it = grid.cells.find(EndGrid::key(x, y));
        if (it == grid.cells.end()) continue;
        for (std::uint32_t id : it->second) {
          if (used[id / 2]) continue;
          const glm::dvec2 near = endPoint(id), far = endPoint(id ^ 1u);
          const double gap = glm::length(near - tip);
          if (gap > o.max_gap_px) continue;
          // The turn into the gap (when there is one) and into the piece both count.
          double bend = turn(dir, far - near);
          if (gap > kSamePoint) bend = std::max(bend, turn(dir, near - tip));
          if (bend > maxTurn) continue;
          const double cost = gap + bend;
          if (cost < best || (cost == best && id < *endId)) {
            best = cost;
            *endId = id;
            found = true;
          }
        }
      }
    return found;
  };
  std::vector<Chain> chains;
  for (std::uint32_t start : order) {
    if (used[start]) continue;
    used[start] = true;
    std::vector<glm::dvec2> forward{segs[start].a, segs[start].b}, backward;
    std::uint8_t kinds = segs[start].kinds;
    bool closed = false;
    // Forward from b, then backward from a (the backward points are prepended at the end).
    for (int side = 0; side < 2 && !closed; ++side) {
      std::vector<glm::dvec2>& pts = side == 0 ? forward : backward;
      glm::dvec2 tip = side == 0 ? segs[start].b : segs[start].a;
      glm::dvec2 dir = side == 0 ? segs[start].b - segs[start].a : segs[start].a - segs[start].b;
      std::uint32_t endId = 0;
      while (nextPiece(tip, dir, &endId)) {
        used[endId / 2] = true;
        kinds |= segs[endId / 2].kinds;
        const glm::dvec2 near = endPoint(endId), far = endPoint(endId ^ 1u);
        if (glm::length(near - tip) > kSamePoint) pts.push_back(near);
        pts.push_back(far);
        dir = far - near;
        tip = far;
      }
      // Closed: the end came back to the start within the gap, turning no more than allowed.
      if (side == 0 && forward.size() > 3) {
        const glm::dvec2 first = forward.front(), second = forward[1];
        const double gap = glm::length(first - tip);
        if (gap <= o.max_gap_px && turn(dir, second - first) <= maxTurn &&
            (gap <= kSamePoint || turn(dir, first - tip) <= maxTurn)) {
          closed = true;
          if (gap <= kSamePoint) forward.pop_back();
        }
      }
    }
    Chain c;
    c.points.assign(backward.rbegin(), backward.rend());
    c.points.insert(c.points.end(), forward.begin(), forward.end());
    c.closed = closed;
    c.kinds = kinds;
    for (std::size_t i = 1; i < c.points.size(); ++i) c.length_px += glm::length(c.points[i] - c.points[i - 1]);
    if (closed) c.length_px += glm::length(c.points.front() - c.points.back());
    chains.push_back(std::move(c));
  }
  return chains;
}

std::vector<glm::dvec2> cardinalSpline(const Chain& chain, double tension, double step) {
  if (!(tension >= -1.0 && tension <= 1.0)) throw makeError("spline tension ", tension, "; expected [-1, 1]");
  if (!(step > 0.0)) throw makeError("spline step ", step, " px; expected > 0");
  const std::vector<glm::dvec2>& p = chain.points;
  const auto n = static_cast<std::ptrdiff_t>(p.size());
  if (n < 2) return p;
  const double s = 0.5 * (1.0 - tension);
  auto at = [&](std::ptrdiff_t i) {
    if (chain.closed) return p[static_cast<std::size_t>(((i % n) + n) % n)];
    return p[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(i, 0, n - 1))];
  };
  std::vector<glm::dvec2> out;
  const std::ptrdiff_t spans = chain.closed ? n : n - 1;
  for (std::ptrdiff_t k = 0; k < spans; ++k) {
    const glm::dvec2 p0 = at(k - 1), p1 = at(k), p2 = at(k + 1), p3 = at(k + 2);
    const int samples = std::max(1, static_cast<int>(std::ceil(glm::length(p2 - p1) / step)));
    for (int j = 0; j < samples; ++j) {
      const double u = static_cast<double>(j) / samples, u2 = u * u, u3 = u2 * u;
      out.push_back(p0 * (-s * u3 + 2 * s * u2 - s * u) + p1 * ((2 - s) * u3 + (s - 3) * u2 + 1) +
                    p2 * ((s - 2) * u3 + (3 - 2 * s) * u2 + s * u) + p3 * (s * u3 - s * u2));
    }
  }
  out.push_back(chain.closed ? p.front() : p.back());
  return out;
}

}  // namespace shanshui::strokes
