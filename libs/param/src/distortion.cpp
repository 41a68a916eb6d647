#include "shanshui/param/distortion.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "shanshui/core/error.h"

namespace shanshui::param {

std::string Distortion::summary() const {
  std::ostringstream s;
  s.precision(4);
  s << "L2 stretch " << l2_stretch << ", Linf " << linf_stretch << ", angle " << angle_distortion << ", area "
    << area_distortion << "; " << flipped << " flipped, " << degenerate << " degenerate";
  if (non_finite > 0) s << ", " << non_finite << " non-finite";
  s << " of " << faces << " faces";
  return s.str();
}

Distortion measureDistortion(const mesh::Mesh& m) {
  SHANSHUI_CHECK_EQ(m.uvs.size(), m.positions.size());
  Distortion d;
  d.faces = static_cast<int>(m.triangles.size());
  struct Face {
    double area3 = 0.0, areaUv = 0.0;  // areaUv signed
    double a = 0.0, b = 0.0, c = 0.0;  // first fundamental form of UV -> surface (raw UV scale)
    bool finite = false;
    bool usable = false;
  };
  std::vector<Face> faces(m.triangles.size());
  double sumPositive = 0.0, sumNegative = 0.0;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const glm::uvec3 t = m.triangles[i];
    const glm::dvec3 q1 = m.positions[t.x], q2 = m.positions[t.y], q3 = m.positions[t.z];
    const glm::dvec2 p1 = m.uvs[t.x], p2 = m.uvs[t.y], p3 = m.uvs[t.z];
    Face& f = faces[i];
    if (!std::isfinite(p1.x + p1.y + p2.x + p2.y + p3.x + p3.y)) {
      ++d.non_finite;
      continue;
    }
    f.finite = true;
    f.area3 = 0.5 * glm::length(glm::cross(q2 - q1, q3 - q1));
    f.areaUv = 0.5 * ((p2.x - p1.x) * (p3.y - p1.y) - (p3.x - p1.x) * (p2.y - p1.y));
    (f.areaUv >= 0 ? sumPositive : sumNegative) += std::abs(f.areaUv);
    if (f.areaUv == 0.0) continue;
    // Sander et al. 2001: partial derivatives of the surface point with respect to s and t.
    const glm::dvec3 ss = (q1 * (p2.y - p3.y) + q2 * (p3.y - p1.y) + q3 * (p1.y - p2.y)) / (2.0 * f.areaUv);
    const glm::dvec3 st = (q1 * (p3.x - p2.x) + q2 * (p1.x - p3.x) + q3 * (p2.x - p1.x)) / (2.0 * f.areaUv);
    f.a = glm::dot(ss, ss);
    f.b = glm::dot(ss, st);
    f.c = glm::dot(st, st);
    f.usable = true;
  }
  const double majority = sumPositive >= sumNegative ? 1.0 : -1.0;
  const double meanUv = (sumPositive + sumNegative) / std::max<std::size_t>(1, faces.size());
  double area3 = 0.0, areaUv = 0.0;
  for (Face& f : faces) {
    if (!f.finite) continue;
    if (!f.usable || std::abs(f.areaUv) <= 1e-12 * meanUv || f.area3 <= 0.0) {
      ++d.degenerate;
      f.usable = false;
      continue;
    }
    if (f.areaUv * majority < 0) ++d.flipped;
    area3 += f.area3;
    areaUv += std::abs(f.areaUv);
  }
  if (area3 <= 0.0) return d;
  // Scaling UV by k scales σ by 1/k; k² = areaUv/area3 makes the two areas equal.
  const double scale2 = areaUv / area3;
  double l2 = 0.0, angle = 0.0, area = 0.0;
  for (const Face& f : faces) {
    if (!f.usable) continue;
    const double root = std::sqrt((f.a - f.c) * (f.a - f.c) + 4.0 * f.b * f.b);
    const double s1 = std::sqrt(std::max(0.0, 0.5 * (f.a + f.c + root)) * scale2);
    const double s2 = std::sqrt(std::max(0.0, 0.5 * (f.a + f.c - root)) * scale2);
    l2 += f.area3 * 0.5 * (s1 * s1 + s2 * s2);
    d.linf_stretch = std::max(d.linf_stretch, s1);
    angle += f.area3 * (s2 > 0.0 ? s1 / s2 : 1e30);
    area += f.area3 * std::abs(std::log(std::max(s1 * s2, 1e-300)));
  }
  d.l2_stretch = std::sqrt(l2 / area3);
  d.angle_distortion = angle / area3;
  d.area_distortion = area / area3;
  return d;
}

}  // namespace shanshui::param
