// Elements grown on a terrain (issue 44): trees and moss dots, each a point of the object's
// surface with a size and an orientation, placed on load from the terrain's slope, height
// and form (ridges, hollows, valley floors), in groves rather than an even scatter, and the
// same for a seed. Geometry only: no GL, so it is tested on the CPU; the renderer's
// elements pass draws them (libs/render/src/passes/elements_pass.cpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "shanshui/mesh/mesh.h"

namespace shanshui::elements {

enum class Kind : std::uint8_t { Pine, Leafy, Bare, Distant, MossDot };
inline constexpr int kTreeKinds = 4;  //!< the kinds before MossDot

//! One element: where it stands (model coordinates of its object: the surface point under
//! it), how big it is and how it is turned. Everything else about its look is grown from
//! its seed (brushwork.h).
struct Instance {
  glm::vec3 position{0.0f};  //!< model units, on the surface
  float size = 1.0f;         //!< trees: height in model units (metres on a DEM); dots: diameter factor
  float lean = 0.0f;         //!< radians from the vertical, in the picture plane (+ leans right)
  Kind kind = Kind::Pine;
  bool mirrored = false;   //!< drawn mirrored left to right
  std::uint32_t seed = 0;  //!< picks and varies its brushwork
};

//! The side (model units, metres on a DEM) past which trees and dots are massed: a hill of a
//! few kilometres keeps its keys as they are.
inline constexpr double kMassedBeyond = 3000.0;

//! Trees (objects.N.trees). Density is per hectare of horizontal area where the site suits
//! trees fully; the site's suitability (siteSuitability) scales it.
struct TreeOptions {
  bool enabled = false;
  double density = 1.5;                  //!< trees per hectare on the best sites, [0, 10000]
  double size = 18.0;                    //!< mean tree height, model units (metres on a DEM), (0, 1e6]
  double size_spread = 0.3;              //!< log-normal sigma of the height, [0, 2]
  double max_slope_deg = 38.0;           //!< no tree on steeper ground, [0, 90]
  std::array<double, 2> band{0.0, 0.5};  //!< height band, fractions of the object's relief, [0, 1]
  double open = 0.15;         //!< density on open slopes relative to ridges, hollows and valley floors, [0, 1]
  double grove = 18.0;        //!< mean trees per grove (1: no groves), [1, 1000]
  double grove_radius = 0.0;  //!< spread of a grove, model units; 0: 6 mean tree heights, [0, 1e6]
  std::array<double, kTreeKinds> kinds{1.0, 1.0, 0.35, 1.0};  //!< shares of pine, leafy, bare, distant
  std::uint64_t seed = 0;                                     //!< 0: the scene's seed
  double ink = 1.0;  //!< drawing: scales the ink of every mark as grown, [0, 1]
  //! Land wider than this (model units, its larger horizontal side) has its trees massed as
  //! a painter masses a far forest (massing()); 0: never, [0, 1e9].
  double massed_beyond = kMassedBeyond;
};

//! Moss dots (objects.N.dots, 苔点): clusters of small dark dabs along ridges, rock edges
//! and at the feet of trees.
struct DotOptions {
  bool enabled = false;
  double density = 0.4;    //!< clusters per hectare on the best sites, [0, 10000]
  double cluster = 5.0;    //!< mean dots per cluster, [1, 100]
  double spread = 0.0;     //!< cluster radius, model units; 0: 0.4 % of the object's larger side
  double at_trees = 0.25;  //!< share of trees with dots at their feet, [0, 1]
  std::uint64_t seed = 0;  //!< 0: the scene's seed
  double size_px = 3.5;    //!< drawing: a dot's size, pixels at 1024 high, [0.5, 64]
  double ink = 1.0;        //!< drawing: a dot's ink, [0, 1]
  //! Land wider than this (model units) keeps massing() of the density; 0: never, [0, 1e9].
  double massed_beyond = kMassedBeyond;
};

//! What a wide landform's trees and dots keep of their keys: f = massed_beyond / side (at
//! most 1; 1 when massed_beyond is 0). At the defaults a volcano 14 km across drew about ten
//! thousand trees and dots of a pixel or two evenly over its slopes, a speckle; massed, its
//! groves hold 1/f times `grove` trees in the same radius (dense clumps, f times as many),
//! open slopes keep f of `open` and the dots f of their density. placeElements applies it.
double massing(double massed_beyond, double side);

//! What a site is, from the terrain around it: each in [0, 1].
struct Site {
  double slope_deg = 0.0;
  double height = 0.0;  //!< fraction of the object's relief
  double ridge = 0.0;   //!< how much the ground stands above its surroundings
  double hollow = 0.0;  //!< how much it lies below them
  double floor = 0.0;   //!< a flat valley floor (a bank, where water would be)
};

//! How well a site suits trees, in [0, 1]: 0 above the slope limit and outside the band,
//! `open` on an open slope, 1 on a ridge, in a hollow or on a valley floor.
double treeSuitability(const Site& s, const TreeOptions& o);
//! How well a site suits moss dots: ridges near the top, steep rock edges.
double dotSuitability(const Site& s);

//! The terrain's form, sampled on a grid over the object's horizontal bounds, with exact
//! surface heights and slopes from the mesh's triangles.
class Terrain {
 public:
  explicit Terrain(const mesh::Mesh& m, int cells = 256);
  //! The surface under (x, y): its highest point there, or false outside the mesh.
  bool surface(double x, double y, glm::dvec3& point, double& slope_deg) const;
  Site site(double x, double y) const;
  const mesh::Bounds& bounds() const { return bounds_; }
  //! Horizontal area the mesh covers, model units².
  double area() const { return area_; }

 private:
  double sample(const std::vector<float>& grid, double x, double y) const;
  const mesh::Mesh& mesh_;
  mesh::Bounds bounds_;
  int nx_ = 0, ny_ = 0;
  double cell_ = 1.0, area_ = 0.0;
  std::vector<std::vector<std::uint32_t>> buckets_;  //!< triangles over each cell
  std::vector<float> height_, ridge_, hollow_, slope_;
};

//! Places the trees, then the dots, of one object on its mesh. Deterministic for the
//! seeds. Throws Error naming `where` when the options would place more than kMaxElements.
std::vector<Instance> placeElements(const mesh::Mesh& m, const TreeOptions& trees, const DotOptions& dots,
                                    std::uint64_t scene_seed, const std::string& where = "object");

inline constexpr std::size_t kMaxElements = 400000;

}  // namespace shanshui::elements
