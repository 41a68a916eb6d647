#include "shanshui/render/camera.h"

#include <algorithm>
#include <cmath>
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

}  // namespace shanshui::render
