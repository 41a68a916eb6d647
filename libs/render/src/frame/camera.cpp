#include "shanshui/render/camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

namespace shanshui::render {

namespace {
double radians(double deg) {
  return deg * std::numbers::pi / 180.0;
}

}  // namespace

glm::dvec3 OrbitCamera::eye() const {
  const double az = radians(azimuth_deg), el = radians(elevation_deg);
  return target + distance * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
}

void OrbitCamera::enclose(const mesh::Bounds& b) {
  const double radius = std::max(0.5 * glm::length(b.size()), 1e-6);
  const glm::dvec3 e = eye();
  const double depth = glm::dot(b.centre() - e, glm::normalize(target - e));
  far_plane = std::max(depth + radius * 1.01, 1e-6);
  near_plane = std::max(depth - radius * 1.01, std::max(distance, glm::length(b.centre() - e)) * 1e-4);
}

glm::mat4 OrbitCamera::view() const {
  return glm::mat4(glm::lookAt(eye(), target, glm::dvec3(0, 0, 1)));
}

glm::mat4 OrbitCamera::projection(double aspect) const {
  return glm::mat4(glm::perspective(radians(fov_y_deg), aspect, near_plane, far_plane));
}

OrbitCamera frameBounds(const mesh::Bounds& b, double azimuth_deg, double elevation_deg, double fov_y_deg,
                        double aspect, double zoom) {
  OrbitCamera cam;
  const double radius = std::max(0.5 * glm::length(b.size()), 1e-6);
  cam.target = glm::dvec3(0.0);
  cam.azimuth_deg = azimuth_deg;
  cam.elevation_deg = elevation_deg;
  cam.fov_y_deg = fov_y_deg;
  cam.distance = radius / std::sin(radians(fov_y_deg) * 0.5);
  if (aspect < 1.0) cam.distance /= aspect;  // keep the whole sphere in a tall frame
  cam.distance /= zoom;
  cam.near_plane = std::max(cam.distance - radius * 1.01, cam.distance * 1e-3);
  cam.far_plane = cam.distance + radius * 1.01;
  return cam;
}

std::vector<glm::dvec2> hullCandidates(const std::vector<glm::dvec2>& points) {
  // Akl and Toussaint's filter: the extreme points along sixteen directions, in counter-
  // clockwise order, span a polygon inside the hull; a point strictly inside it is not a
  // vertex of the hull. Points on an edge are kept; a direction whose extreme is its
  // neighbour's adds no edge.
  // Sixteen directions leave about 3 % of a disc's points, eight about 10 %.
  constexpr int kDirections = 16;
  if (points.size() <= kDirections) return points;
  std::array<glm::dvec2, kDirections> direction, extreme;
  std::array<double, kDirections> best;
  for (int k = 0; k < kDirections; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kDirections;
    direction[k] = glm::dvec2(std::cos(a), std::sin(a));
  }
  best.fill(-std::numeric_limits<double>::infinity());
  for (const glm::dvec2& p : points)
    for (int k = 0; k < kDirections; ++k) {
      const double along = glm::dot(p, direction[k]);
      if (along > best[k]) {
        best[k] = along;
        extreme[k] = p;
      }
    }
  int edges = 0;
  for (int k = 0; k < kDirections; ++k) edges += extreme[k] != extreme[(k + 1) % kDirections] ? 1 : 0;
  if (edges < 3) return points;  // all on a line or at one point: no inside
  std::vector<glm::dvec2> kept;
  for (const glm::dvec2& p : points) {
    bool inside = true;
    for (int k = 0; k < kDirections && inside; ++k) {
      const glm::dvec2 a = extreme[k], e = extreme[(k + 1) % kDirections] - a, d = p - a;
      inside = (e.x == 0.0 && e.y == 0.0) || e.x * d.y - e.y * d.x > 0.0;
    }
    if (!inside) kept.push_back(p);
  }
  return kept;
}

OrbitCamera fillPoints(const std::vector<glm::dvec3>& points, double azimuth_deg, double elevation_deg,
                       double fov_y_deg, double aspect, double zoom) {
  const mesh::Bounds b = mesh::bounds(points);
  OrbitCamera cam;
  cam.azimuth_deg = azimuth_deg;
  cam.elevation_deg = elevation_deg;
  cam.fov_y_deg = fov_y_deg;
  // Camera basis: f from the eye towards the target, r to the right, u up.
  const double az = radians(azimuth_deg), el = radians(elevation_deg);
  const glm::dvec3 f = -glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0, 0, 1)));
  const glm::dvec3 u = glm::cross(r, f);
  constexpr double kMargin = 0.94;  // the points' picture fills 94 % of the frame
  const double radius = std::max(0.5 * glm::length(b.size()), 1e-6);
  const double ty = kMargin * std::tan(radians(fov_y_deg) * 0.5), tx = ty * aspect;
  // A point (x, y, z) in the basis, seen from the eye (ex, ey, ez), is in the frame when
  // |x - ex| <= tx (z - ez) and |y - ey| <= ty (z - ez). The four supporting planes give
  // the eye's place: each pair fixes how far back the eye must be and where it is centred.
  double a = -1e300, bb = -1e300, c = -1e300, d = -1e300;
  for (const glm::dvec3& q : points) {
    const glm::dvec3 p = q - b.centre();
    const double x = glm::dot(p, r), y = glm::dot(p, u), z = glm::dot(p, f);
    a = std::max(a, x - tx * z);
    bb = std::max(bb, -x - tx * z);
    c = std::max(c, y - ty * z);
    d = std::max(d, -y - ty * z);
  }
  const double ez_x = -(a + bb) / (2 * tx), ez_y = -(c + d) / (2 * ty);
  const double ez = std::min(ez_x, ez_y);
  double ex = 0.5 * (a - bb), ey = 0.5 * (c - d);
  // The other axis has room; centre the points' picture in it. The sum of its picture's two
  // extremes falls as the eye moves along that axis: bisect for zero.
  const bool x_has_room = ez < ez_x;
  const glm::dvec3 side = x_has_room ? r : u;
  // Each point as (along the side, along the view): the extremes of the ratio below over
  // all points are those over the candidates (a drawn framing has thousands of points, and
  // the bisection visits them 80 times; issue 47 measured 1.6 ms a frame).
  std::vector<glm::dvec2> projected;
  projected.reserve(points.size());
  for (const glm::dvec3& q : points) {
    const glm::dvec3 p = q - b.centre();
    projected.emplace_back(glm::dot(p, side), glm::dot(p, f));
  }
  const std::vector<glm::dvec2> candidates = hullCandidates(projected);
  double lo = -2 * radius, hi = 2 * radius;
  for (int step = 0; step < 80; ++step) {
    const double mid = 0.5 * (lo + hi);
    double most = -1e300, least = 1e300;
    for (const glm::dvec2& p : candidates) {
      const double s = (p.x - mid) / (p.y - ez);
      most = std::max(most, s);
      least = std::min(least, s);
    }
    (most + least > 0 ? lo : hi) = mid;
  }
  (x_has_room ? ex : ey) = 0.5 * (lo + hi);
  cam.target = b.centre() + ex * r + ey * u;
  cam.distance = std::max(-ez, 1e-3 * radius) / zoom;
  cam.enclose(b);
  return cam;
}

OrbitCamera fillBounds(const mesh::Bounds& b, double azimuth_deg, double elevation_deg, double fov_y_deg, double aspect,
                       double zoom) {
  std::vector<glm::dvec3> corners;
  for (int c = 0; c < 8; ++c) corners.push_back(b.corner(c));
  return fillPoints(corners, azimuth_deg, elevation_deg, fov_y_deg, aspect, zoom);
}

Relief::Relief(const std::vector<glm::dvec3>& points, int cells) {
  if (points.empty() || cells < 1) return;
  bounds_ = mesh::bounds(points);
  summit_ = *std::max_element(points.begin(), points.end(),
                              [](const glm::dvec3& p, const glm::dvec3& q) { return p.z < q.z; });
  cells_ = cells;
  top_.assign(static_cast<std::size_t>(cells) * cells, std::numeric_limits<double>::quiet_NaN());
  const glm::dvec3 size = glm::max(bounds_.size(), glm::dvec3(1e-300));
  for (const glm::dvec3& p : points) {
    const int i = std::clamp(static_cast<int>((p.x - bounds_.min.x) / size.x * cells), 0, cells - 1);
    const int j = std::clamp(static_cast<int>((p.y - bounds_.min.y) / size.y * cells), 0, cells - 1);
    double& t = top_[static_cast<std::size_t>(j) * cells + i];
    if (!(t >= p.z)) t = p.z;  // NaN compares false: the first point fills the cell
  }
}

double Relief::groundAt(glm::dvec2 xy, double radius) const {
  double ground = bounds_.min.z;
  if (empty()) return ground;
  const glm::dvec3 size = glm::max(bounds_.size(), glm::dvec3(1e-300));
  auto cell = [&](double v, double lo, double extent) {
    return static_cast<int>(std::floor((v - lo) / extent * cells_));
  };
  const int i0 = std::max(cell(xy.x - radius, bounds_.min.x, size.x), 0);
  const int i1 = std::min(cell(xy.x + radius, bounds_.min.x, size.x), cells_ - 1);
  const int j0 = std::max(cell(xy.y - radius, bounds_.min.y, size.y), 0);
  const int j1 = std::min(cell(xy.y + radius, bounds_.min.y, size.y), cells_ - 1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const double t = top_[static_cast<std::size_t>(j) * cells_ + i];
      if (t > ground) ground = t;
    }
  }
  return ground;
}

OrbitCamera highDistance(const Relief& relief, double azimuth_deg, double fov_y_deg, double zoom, bool over_ranges) {
  const mesh::Bounds& b = relief.bounds();
  const glm::dvec3 summit = relief.summit();
  const double relief_height = std::max(b.size().z, 1e-6);
  const double footprint = std::max(0.5 * glm::length(glm::dvec2(b.size())), relief_height);
  const double az = radians(azimuth_deg);
  const glm::dvec2 away(std::cos(az), std::sin(az));
  constexpr double kSummitAngleDeg = 18.0;
  // The eye stands at the foot of the land, outside its footprint where it can (so no
  // slope fills the foreground), and far enough that the summit rises 18° above the
  // bottom of the land; then it is lifted clear of the ground where it stands.
  glm::dvec2 exit(1e300);  // distance along `away` from the summit to the bounds' edge
  for (int axis = 0; axis < 2; ++axis) {
    if (std::abs(away[axis]) > 1e-12) {
      const double edge = away[axis] > 0 ? b.max[axis] : b.min[axis];
      exit[axis] = (edge - summit[axis]) / away[axis];
    }
  }
  const double base_z = b.min.z + 0.05 * relief_height;
  const double horizontal =
      std::max((summit.z - base_z) / std::tan(radians(kSummitAngleDeg)), std::min(exit.x, exit.y) + 0.05 * footprint);
  const glm::dvec2 at = glm::dvec2(summit) + horizontal * away;
  // Clear of the ground where it stands and of the land's edge in front of it: an eye below
  // the edge would see the underside of the surface.
  const glm::dvec2 edge = glm::dvec2(summit) + std::min({exit.x, exit.y, horizontal}) * away;
  const double ground = std::max(relief.groundAt(at, 0.03 * footprint), relief.groundAt(edge, 0.03 * footprint));
  double eye_z = std::max(base_z, ground + 0.03 * relief_height);
  if (over_ranges) {
    for (int k = 0; k <= 48; ++k) {
      const glm::dvec2 p = at + (0.6 * k / 48.0) * (glm::dvec2(summit) - at);
      eye_z = std::max(eye_z, relief.groundAt(p, 0.01 * footprint) + 0.03 * relief_height);
    }
  }
  const glm::dvec3 eye(at, eye_z);

  OrbitCamera cam;
  cam.azimuth_deg = azimuth_deg;
  const double to_summit = std::atan2(summit.z - eye_z, horizontal) * 180.0 / std::numbers::pi;
  // The summit 0.3 of the field above the middle (about 0.8 of the height), the view tilted
  // up by at least a quarter of the summit's angle: a far peak is seen through a narrower
  // field rather than looked down on. Zoom then narrows the field around the summit.
  const double field = std::min(fov_y_deg, 0.75 * to_summit / 0.3);
  cam.fov_y_deg =
      std::clamp(2.0 * std::atan(std::tan(radians(field) * 0.5) / zoom) * 180.0 / std::numbers::pi, 0.5, 170.0);
  const double pitch = to_summit - 0.3 * cam.fov_y_deg;
  cam.elevation_deg = -pitch;
  // Aim at the point of that pitch above the summit's foot, at the summit's distance.
  cam.distance = horizontal / std::cos(radians(pitch));
  const double el = radians(cam.elevation_deg);
  cam.target = eye - cam.distance * glm::dvec3(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  cam.enclose(b);
  return cam;
}

}  // namespace shanshui::render
