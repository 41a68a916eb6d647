#include "shanshui/param/uv_adjust.h"

#include <algorithm>
#include <cmath>

#include "shanshui/core/error.h"

namespace shanshui::param {
namespace {

glm::dvec2 minimum(const mesh::Mesh& m, glm::dvec2* maximum) {
  glm::dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const glm::vec2& uv : m.uvs) {
    lo = glm::min(lo, glm::dvec2(uv));
    hi = glm::max(hi, glm::dvec2(uv));
  }
  if (maximum) *maximum = hi;
  return lo;
}

}  // namespace

void scaleToTexelSize(mesh::Mesh& m, double worldSize) {
  if (!(worldSize > 0.0) || !std::isfinite(worldSize)) {
    throw makeError("texel size ", worldSize, "; expected a positive length in mesh units");
  }
  SHANSHUI_CHECK_EQ(m.uvs.size(), m.positions.size());
  double area3 = 0.0, areaUv = 0.0;
  for (const glm::uvec3& t : m.triangles) {
    area3 += 0.5 * glm::length(glm::cross(m.positions[t.y] - m.positions[t.x], m.positions[t.z] - m.positions[t.x]));
    const glm::dvec2 a = m.uvs[t.x], b = m.uvs[t.y], c = m.uvs[t.z];
    areaUv += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
  }
  if (!(areaUv > 0.0)) throw makeError("texel size: the UVs have zero area");
  // Surface units per UV unit on average, then UV units per texture repeat.
  const double k = std::sqrt(area3 / areaUv) / worldSize;
  const glm::dvec2 lo = minimum(m, nullptr);
  for (glm::vec2& uv : m.uvs) uv = glm::vec2((glm::dvec2(uv) - lo) * k);
}

void normalizeUvs(mesh::Mesh& m) {
  glm::dvec2 hi;
  const glm::dvec2 lo = minimum(m, &hi);
  const double side = std::max(hi.x - lo.x, hi.y - lo.y);
  if (!(side > 0.0)) throw makeError("normalize: the UVs span no area");
  for (glm::vec2& uv : m.uvs) uv = glm::vec2((glm::dvec2(uv) - lo) / side);
}

}  // namespace shanshui::param
