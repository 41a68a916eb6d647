// Anytime refinement of a one-piece UV map by as-rigid-as-possible iterations (Liu et al.
// 2008), for auto's budget: CGAL's ARAP_parameterizer_3 runs a fixed number of iterations,
// each a direct solve, from its own starting map, so it can neither start from the best map
// auto already has nor stop when the time is up. This one is written by hand on Eigen: the
// global step is a few conjugate-gradient iterations warm-started from the current map, and
// the clock is read between them.
#pragma once

#include <chrono>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "shanshui/mesh/mesh.h"

namespace shanshui::param::detail {

struct RefineResult {
  int iterations = 0;         //!< local-global rounds begun
  double energy_start = 0.0;  //!< ARAP energy of the map it started from
  double energy_end = 0.0;
  bool converged = false;  //!< stopped because a round lowered the energy by under `tolerance` (relative)
  bool enough = false;     //!< stopped because `enough` said so
};

//! Lowers the ARAP energy Σ_t A_t ‖J_t − R_t‖² of `uv` (one per vertex of `m`, a clean
//! triangle mesh) until `deadline`, until a round lowers it by less than `tolerance` of its
//! value, or until `enough` (asked after each round with the map so far, when given) says
//! the map is good enough. Every conjugate-gradient iteration lowers the energy, so
//! stopping at any time leaves a map at least as good by this energy as the one given
//! (stretch and flips are for the caller to measure). Vertex 0 is held near its place.
RefineResult refineArap(const mesh::Mesh& m, std::vector<glm::dvec2>& uv,
                        std::chrono::steady_clock::time_point deadline, double tolerance = 1e-5,
                        const std::function<bool(const std::vector<glm::dvec2>&)>& enough = {});

}  // namespace shanshui::param::detail
