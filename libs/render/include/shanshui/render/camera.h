// An orbit camera around a target, Z up (terrain convention: x east, y north, z up).
#pragma once

#include <vector>

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
  //! Sets the near and far planes around the bounding sphere of `b` as seen from here (the
  //! near plane at least 1e-4 of the way to it).
  void enclose(const mesh::Bounds& b);
  glm::mat4 view() const;
  glm::mat4 projection(double aspect) const;
};

//! A camera that frames the bounding sphere of `b` (relative to b's centre, which becomes
//! the origin of the uploaded mesh), from the given azimuth and elevation, in a frame of
//! the given aspect (width / height); zoom > 1 moves it closer. Near and far planes
//! enclose the sphere.
OrbitCamera frameBounds(const mesh::Bounds& b, double azimuth_deg, double elevation_deg, double fov_y_deg = 35.0,
                        double aspect = 1.0, double zoom = 1.0);

//! A camera, in the coordinates of `b`, whose view from the given azimuth and elevation
//! holds the eight corners of `b` with a small margin and touches the frame on two sides
//! (the box's picture centred in the other direction); zoom > 1 moves it closer.
OrbitCamera fillBounds(const mesh::Bounds& b, double azimuth_deg, double elevation_deg, double fov_y_deg = 35.0,
                       double aspect = 1.0, double zoom = 1.0);

//! As fillBounds, for the picture of a set of points (what is drawn of the land) instead of
//! a box's eight corners.
OrbitCamera fillPoints(const std::vector<glm::dvec3>& points, double azimuth_deg, double elevation_deg,
                       double fov_y_deg = 35.0, double aspect = 1.0, double zoom = 1.0);

//! The points of a plane that can be a vertex of their convex hull: all but those strictly
//! inside the polygon of the extreme points along sixteen directions (Akl and Toussaint's
//! filter, linear time). The largest and smallest of a ratio of two affine functions of a
//! point over all points (its denominator positive) are those over these.
std::vector<glm::dvec2> hullCandidates(const std::vector<glm::dvec2>& points);

//! The scene's land seen from above, coarsely: its highest point, and the highest ground
//! in each cell of a grid over its horizontal bounds. Enough to place a camera on the
//! ground and aim it at a peak.
class Relief {
 public:
  Relief() = default;
  //! Points of the scene's surfaces (world coordinates); `cells` per side of the grid.
  Relief(const std::vector<glm::dvec3>& points, int cells = 32);
  bool empty() const { return top_.empty(); }
  const mesh::Bounds& bounds() const { return bounds_; }
  glm::dvec3 summit() const { return summit_; }
  //! The highest ground in the cells within `radius` of (x, y); the lowest point of the
  //! scene outside the grid or where no point fell.
  double groundAt(glm::dvec2 xy, double radius) const;

 private:
  mesh::Bounds bounds_;
  glm::dvec3 summit_{0.0};
  int cells_ = 0;
  std::vector<double> top_;  //!< cells_², row-major in y; NaN where no point fell
};

//! High distance (gao yuan): a camera standing on the ground, from the given azimuth
//! around the highest peak, far enough that the summit is seen 18° above the horizon, and
//! pitched up so the summit sits near the top of the frame. zoom > 1 narrows the field.
//! `over_ranges` (a composition of several ranges): the eye rises until its level clears the
//! land on the nearer 60 % of its way to the summit, so the near ranges lie below the view
//! instead of filling it.
OrbitCamera highDistance(const Relief& relief, double azimuth_deg, double fov_y_deg, double zoom,
                         bool over_ranges = false);

}  // namespace shanshui::render
