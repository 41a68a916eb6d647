// An orbit camera around a target, Z up (terrain convention: x east, y north, z up).
#pragma once

#include <glm/glm.hpp>

#include "shanshui/mesh/mesh.h"

namespace shanshui::render {

struct OrbitCamera {
  glm::dvec3 target{0.0};
  double distance = 10.0;       //!< from the target, > 0
  double azimuth_deg = -60.0;   //!< around +Z, 0 looks from +X towards the target
  double elevation_deg = 25.0;  //!< above the horizon, (-90, 90)
  double fov_y_deg = 35.0;      //!< vertical field of view, (0, 180)
  double near_plane = 0.1;
  double far_plane = 100.0;

  glm::dvec3 eye() const;
  glm::mat4 view() const;
  glm::mat4 projection(double aspect) const;
};

//! A camera that frames the bounding sphere of `b` (relative to b's centre, which becomes
//! the origin of the uploaded mesh), from the given azimuth and elevation, in a frame of
//! the given aspect (width / height); zoom > 1 moves it closer. Near and far planes
//! enclose the sphere.
OrbitCamera frameBounds(const mesh::Bounds& b, double azimuth_deg, double elevation_deg, double fov_y_deg = 35.0,
                        double aspect = 1.0, double zoom = 1.0);

}  // namespace shanshui::render
