#include "shanshui/strokes/visibility.h"

#include <algorithm>
#include <cmath>

#include "shanshui/core/error.h"
#include "shanshui/core/parallel_for.h"

namespace shanshui::strokes {
namespace {

// Window coordinates (x, y in pixels, z in [0, 1]) and clip w of a point.
glm::dvec4 toWindow(const glm::dmat4& vp, glm::dvec3 p, int width, int height) {
  const glm::dvec4 c = vp * glm::dvec4(p, 1.0);
  if (!(c.w > 0.0)) return glm::dvec4(0.0, 0.0, 0.0, -1.0);
  const glm::dvec3 ndc = glm::dvec3(c) / c.w;
  return {(ndc.x * 0.5 + 0.5) * width, (ndc.y * 0.5 + 0.5) * height, ndc.z * 0.5 + 0.5, c.w};
}

}  // namespace

ReferenceImage rasterizeReference(const mesh::Mesh& m, const glm::dmat4& vp, int width, int height) {
  if (width <= 0 || height <= 0) throw makeError("reference image ", width, "x", height, "; expected a positive size");
  ReferenceImage img;
  img.width = width;
  img.height = height;
  img.id.assign(static_cast<std::size_t>(width) * height, -1);
  img.depth.assign(img.id.size(), 1.0f);
  std::vector<glm::dvec4> w(m.positions.size());
  for (std::size_t i = 0; i < w.size(); ++i) w[i] = toWindow(vp, m.positions[i], width, height);
  for (std::size_t f = 0; f < m.triangles.size(); ++f) {
    const glm::uvec3 t = m.triangles[f];
    const glm::dvec4 p0 = w[t.x], p1 = w[t.y], p2 = w[t.z];
    if (p0.w <= 0 || p1.w <= 0 || p2.w <= 0) continue;  // crosses the eye plane: not drawn
    const double area = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
    if (area == 0.0) continue;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({p0.x, p1.x, p2.x}))));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({p0.x, p1.x, p2.x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({p0.y, p1.y, p2.y}))));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({p0.y, p1.y, p2.y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        // Barycentric weights; both orientations are drawn (no culling).
        const double b0 = ((p1.x - px) * (p2.y - py) - (p2.x - px) * (p1.y - py)) / area;
        const double b1 = ((p2.x - px) * (p0.y - py) - (p0.x - px) * (p2.y - py)) / area;
        const double b2 = 1.0 - b0 - b1;
        if (b0 < 0 || b1 < 0 || b2 < 0) continue;
        const double z = b0 * p0.z + b1 * p1.z + b2 * p2.z;  // window z is affine on screen
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        if (z < img.depth[i]) {
          img.depth[i] = static_cast<float>(z);
          img.id[i] = static_cast<std::int32_t>(f);
        }
      }
  }
  return img;
}

std::vector<ScreenSegment> visibleSegments(const std::vector<FeatureEdge>& edges, const EdgeGraph& g,
                                           const mesh::Mesh& m, const glm::dmat4& vp, const ReferenceImage& ref,
                                           const VisibilityOptions& o) {
  if (!(o.samples_per_pixel > 0.0) || o.search_px < 0 || !(o.depth_tolerance >= 0.0)) {
    throw makeError("visibility options: samples per pixel ", o.samples_per_pixel, ", search ", o.search_px,
                    " px, depth tolerance ", o.depth_tolerance, "; expected > 0, >= 0, >= 0");
  }
  const bool linear = o.near > 0.0 && o.far > o.near;
  // Eye distance of a window depth under a perspective projection with GL's default range.
  auto distance = [&](double z) {
    return 2.0 * o.near * o.far / (o.far + o.near - (2.0 * z - 1.0) * (o.far - o.near));
  };
  auto inFront = [&](double sample, float image) {
    if (!linear) return sample <= image + o.depth_tolerance;
    const double d = distance(sample), di = distance(image);
    return d <= di * (1.0 + o.relative_tolerance);
  };
  // Edges in chunks on every core, gathered in order.
  const int chunks = std::max(1, std::min<int>(64, static_cast<int>(edges.size() / 256)));
  std::vector<std::vector<ScreenSegment>> parts(static_cast<std::size_t>(chunks));
  parallelFor(chunks, resolveThreads(0), [&](int chunk) {
    std::vector<ScreenSegment>& out = parts[static_cast<std::size_t>(chunk)];
    const std::size_t begin = edges.size() * chunk / chunks, end = edges.size() * (chunk + 1) / chunks;
    for (std::size_t e = begin; e < end; ++e) {
      const FeatureEdge& fe = edges[e];
      const glm::dvec4 a = toWindow(vp, m.positions[g.vertices[fe.edge][0]], ref.width, ref.height);
      const glm::dvec4 b = toWindow(vp, m.positions[g.vertices[fe.edge][1]], ref.width, ref.height);
      if (a.w <= 0 || b.w <= 0) continue;
      const auto [f0, f1] = g.faces[fe.edge];
      const double length = glm::length(glm::dvec2(b) - glm::dvec2(a));
      const int n = std::max(2, static_cast<int>(std::ceil(length * o.samples_per_pixel)) + 1);
      // Runs of visible samples become segments from the first to the last sample of the run.
      int runStart = -1;
      auto close = [&](int last) {
        const double t0 = static_cast<double>(runStart) / (n - 1), t1 = static_cast<double>(last) / (n - 1);
        const glm::dvec3 p = glm::mix(glm::dvec3(a), glm::dvec3(b), t0), q = glm::mix(glm::dvec3(a), glm::dvec3(b), t1);
        const bool whole = runStart == 0 && last == n - 1;
        if (whole || glm::length(glm::dvec2(q) - glm::dvec2(p)) >= o.min_partial_px) {
          out.push_back({glm::dvec2(p), glm::dvec2(q), p.z, q.z, fe.edge, fe.kinds});
        }
        runStart = -1;
      };
      for (int s = 0; s < n; ++s) {
        const double t = static_cast<double>(s) / (n - 1);
        const glm::dvec3 p = glm::mix(glm::dvec3(a), glm::dvec3(b), t);  // window z is affine along the edge too
        const int px = static_cast<int>(std::floor(p.x)), py = static_cast<int>(std::floor(p.y));
        bool visible = false;
        for (int dy = -o.search_px; dy <= o.search_px && !visible; ++dy)
          for (int dx = -o.search_px; dx <= o.search_px && !visible; ++dx) {
            const int x = px + dx, y = py + dy;
            if (x < 0 || y < 0 || x >= ref.width || y >= ref.height) continue;
            const std::size_t i = static_cast<std::size_t>(y) * ref.width + x;
            visible = ref.id[i] == f0 || (f1 >= 0 && ref.id[i] == f1) || inFront(p.z, ref.depth[i]);
          }
        if (visible && runStart < 0) runStart = s;
        if (!visible && runStart >= 0) close(s - 1);
      }
      if (runStart >= 0) close(n - 1);
    }
  });
  std::vector<ScreenSegment> out;
  for (auto& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

}  // namespace shanshui::strokes
