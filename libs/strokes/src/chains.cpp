#include "shanshui/strokes/chains.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "shanshui/core/error.h"

namespace shanshui::strokes {
namespace {

constexpr double kSamePoint = 1e-6;  // pixels: pieces of one edge, or of edges that meet

double turn(glm::dvec2 from, glm::dvec2 to) {
  const double lf = glm::length(from), lt = glm::length(to);
  if (lf == 0.0 || lt == 0.0) return 0.0;
  return std::acos(std::clamp(glm::dot(from, to) / (lf * lt), -1.0, 1.0));
}

// Piece ends binned on a dense grid over their bounding box (compressed rows: each cell's
// ends lie together), for the neighbour search.
struct EndGrid {
  double cell = 1.0;
  glm::dvec2 origin{0.0};
  std::int64_t nx = 1, ny = 1;
  std::vector<std::uint32_t> start;  // per cell, into ids; one more at the end
  std::vector<std::uint32_t> ids;
  std::int64_t cx(double x) const { return static_cast<std::int64_t>(std::floor((x - origin.x) / cell)); }
  std::int64_t cy(double y) const { return static_cast<std::int64_t>(std::floor((y - origin.y) / cell)); }
  void build(const std::vector<glm::dvec2>& points, double cellSize) {
    cell = cellSize;
    glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const glm::dvec2& p : points) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    if (points.empty()) lo = hi = glm::dvec2(0.0);
    origin = lo;
    // Bounded cell count: a huge span (points far off screen) coarsens the grid instead.
    cell = std::max(cell, std::max(hi.x - lo.x, hi.y - lo.y) / 4096.0);
    nx = cx(hi.x) + 1;
    ny = cy(hi.y) + 1;
    start.assign(static_cast<std::size_t>(nx * ny + 1), 0);
    for (const glm::dvec2& p : points) ++start[static_cast<std::size_t>(cy(p.y) * nx + cx(p.x)) + 1];
    for (std::size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
    ids.resize(points.size());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < points.size(); ++i)
      ids[fill[static_cast<std::size_t>(cy(points[i].y) * nx + cx(points[i].x))]++] = i;
  }
  template <typename F>
  void forEachIn(std::int64_t x, std::int64_t y, F&& f) const {
    if (x < 0 || y < 0 || x >= nx || y >= ny) return;
    const std::size_t c = static_cast<std::size_t>(y * nx + x);
    for (std::uint32_t k = start[c]; k < start[c + 1]; ++k) f(ids[k]);
  }
};

}  // namespace

std::vector<Chain> linkSegments(const std::vector<ScreenSegment>& segs, const LinkOptions& o) {
  if (!(o.max_turn_deg >= 0.0 && o.max_turn_deg <= 180.0)) {
    throw makeError("link turn ", o.max_turn_deg, " degrees; expected [0, 180]");
  }
  if (!(o.max_gap_px >= 0.0 && o.max_gap_px <= 1000.0))
    throw makeError("link gap ", o.max_gap_px, " px; expected [0, 1000]");
  const double maxTurn = o.max_turn_deg * M_PI / 180.0;
  auto endPoint = [&](std::uint32_t id) { return id % 2 == 0 ? segs[id / 2].a : segs[id / 2].b; };
  auto endDepth = [&](std::uint32_t id) { return id % 2 == 0 ? segs[id / 2].za : segs[id / 2].zb; };
  std::vector<glm::dvec2> ends(2 * segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i) {
    ends[2 * i] = segs[i].a;
    ends[2 * i + 1] = segs[i].b;
  }
  EndGrid grid;
  grid.build(ends, std::max(o.max_gap_px, 1.0));
  const double minCos = std::cos(maxTurn);
  // Within the turn: compared by cosine, so the arc cosine is taken only for candidates.
  auto within = [&](glm::dvec2 from, glm::dvec2 to) {
    const double lf = glm::length(from), lt = glm::length(to);
    return lf == 0.0 || lt == 0.0 || glm::dot(from, to) >= minCos * lf * lt - 1e-12 * lf * lt;
  };
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
    const std::int64_t cx = grid.cx(tip.x), cy = grid.cy(tip.y);
    for (std::int64_t y = cy - 1; y <= cy + 1; ++y)
      for (std::int64_t x = cx - 1; x <= cx + 1; ++x) {
        grid.forEachIn(x, y, [&](std::uint32_t id) {
          if (used[id / 2]) return;
          const glm::dvec2 near = endPoint(id), far = endPoint(id ^ 1u);
          const double gap = glm::length(near - tip);
          if (gap > o.max_gap_px) return;
          // The turn into the gap (when there is one) and into the piece both count.
          if (!within(dir, far - near) || (gap > kSamePoint && !within(dir, near - tip))) return;
          double bend = turn(dir, far - near);
          if (gap > kSamePoint) bend = std::max(bend, turn(dir, near - tip));
          const double cost = gap + bend;
          if (cost < best || (cost == best && id < *endId)) {
            best = cost;
            *endId = id;
            found = true;
          }
        });
      }
    return found;
  };
  std::vector<Chain> chains;
  for (std::uint32_t start : order) {
    if (used[start]) continue;
    used[start] = true;
    std::vector<glm::dvec2> forward{segs[start].a, segs[start].b}, backward;
    std::vector<double> forwardDepth{segs[start].za, segs[start].zb}, backwardDepth;
    std::uint8_t kinds = segs[start].kinds;
    bool closed = false;
    // Forward from b, then backward from a (the backward points are prepended at the end).
    for (int side = 0; side < 2 && !closed; ++side) {
      std::vector<glm::dvec2>& pts = side == 0 ? forward : backward;
      std::vector<double>& depths = side == 0 ? forwardDepth : backwardDepth;
      glm::dvec2 tip = side == 0 ? segs[start].b : segs[start].a;
      glm::dvec2 dir = side == 0 ? segs[start].b - segs[start].a : segs[start].a - segs[start].b;
      std::uint32_t endId = 0;
      while (nextPiece(tip, dir, &endId)) {
        used[endId / 2] = true;
        kinds |= segs[endId / 2].kinds;
        const glm::dvec2 near = endPoint(endId), far = endPoint(endId ^ 1u);
        if (glm::length(near - tip) > kSamePoint) {
          pts.push_back(near);
          depths.push_back(endDepth(endId));
        }
        pts.push_back(far);
        depths.push_back(endDepth(endId ^ 1u));
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
          if (gap <= kSamePoint) {
            forward.pop_back();
            forwardDepth.pop_back();
          }
        }
      }
    }
    Chain c;
    c.points.assign(backward.rbegin(), backward.rend());
    c.points.insert(c.points.end(), forward.begin(), forward.end());
    c.depth.assign(backwardDepth.rbegin(), backwardDepth.rend());
    c.depth.insert(c.depth.end(), forwardDepth.begin(), forwardDepth.end());
    c.closed = closed;
    c.kinds = kinds;
    for (std::size_t i = 1; i < c.points.size(); ++i) c.length_px += glm::length(c.points[i] - c.points[i - 1]);
    if (closed) c.length_px += glm::length(c.points.front() - c.points.back());
    chains.push_back(std::move(c));
  }
  return chains;
}

Chain subdivided(const Chain& chain, double maxSpan) {
  if (!(maxSpan > 0.0)) throw makeError("chain span ", maxSpan, " px; expected > 0");
  Chain out = chain;
  out.points.clear();
  out.depth.clear();
  const std::size_t n = chain.points.size();
  const bool withDepth = chain.depth.size() == n;
  const std::size_t spans = chain.closed ? n : (n == 0 ? 0 : n - 1);
  for (std::size_t k = 0; k < spans; ++k) {
    const glm::dvec2 a = chain.points[k], b = chain.points[(k + 1) % n];
    const int parts = std::max(1, static_cast<int>(std::ceil(glm::length(b - a) / maxSpan)));
    for (int j = 0; j < parts; ++j) {
      const double t = static_cast<double>(j) / parts;
      out.points.push_back(glm::mix(a, b, t));
      if (withDepth) out.depth.push_back((1 - t) * chain.depth[k] + t * chain.depth[(k + 1) % n]);
    }
  }
  if (!chain.closed && n > 0) {
    out.points.push_back(chain.points.back());
    if (withDepth) out.depth.push_back(chain.depth.back());
  }
  return out;
}

std::vector<glm::dvec2> cardinalSpline(const Chain& chain, double tension, double step, std::vector<double>* depth) {
  if (!(tension >= -1.0 && tension <= 1.0)) throw makeError("spline tension ", tension, "; expected [-1, 1]");
  if (!(step > 0.0)) throw makeError("spline step ", step, " px; expected > 0");
  const std::vector<glm::dvec2>& p = chain.points;
  const auto n = static_cast<std::ptrdiff_t>(p.size());
  const bool withDepth = depth != nullptr && chain.depth.size() == p.size();
  if (depth) depth->clear();
  if (n < 2) {
    if (withDepth) *depth = chain.depth;
    return p;
  }
  const double s = 0.5 * (1.0 - tension);
  auto depthAt = [&](std::ptrdiff_t i) { return chain.depth[static_cast<std::size_t>(((i % n) + n) % n)]; };
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
      if (withDepth) depth->push_back((1.0 - u) * depthAt(k) + u * depthAt(k + 1));
    }
  }
  out.push_back(chain.closed ? p.front() : p.back());
  if (withDepth) depth->push_back(chain.closed ? chain.depth.front() : chain.depth.back());
  return out;
}

}  // namespace shanshui::strokes
