// Linking visible edge pieces into long strokes (seed 002: turn <= 45°, gap <= 5 px) and
// the Cardinal spline a brush follows along a chain.
#pragma once

#include <cstdint>
#include <vector>

#include "shanshui/strokes/visibility.h"

namespace shanshui::strokes {

struct LinkOptions {
  double max_turn_deg = 45.0;  //!< [0, 180]: the direction may turn this much where pieces join
  double max_gap_px = 5.0;     //!< [0, 1000]: the next piece must start this close to the chain's end
};

//! A polyline on screen, in drawing order.
struct Chain {
  std::vector<glm::dvec2> points;
  std::vector<double> depth;  //!< window depth per point
  bool closed = false;        //!< the last point joins the first
  std::uint8_t kinds = 0;     //!< union of the edge kinds in it
  double length_px = 0.0;
};

//! Greedy linking: the longest unused piece starts a chain, which grows at its end and then
//! at its start by the unused piece whose near end is closest (gap plus the turn, in
//! pixels per radian of turn) among those within the gap and the turn; a chain whose ends
//! meet that way is closed. Deterministic for a given input order.
std::vector<Chain> linkSegments(const std::vector<ScreenSegment>& segments, const LinkOptions& options = {});

//! The chain with points added so that no span is longer than max_span_px: a spline through
//! the pieces' ends alone swings far off long straight pieces (a cube's edge is one piece).
Chain subdivided(const Chain& chain, double max_span_px);

//! Points of the Cardinal spline through a chain's points (seed 002 Eq. 3-20, with the
//! last term read as s·u³ − s·u²: the printed one does not pass through the points),
//! s = (1 − tension) / 2, sampled about every `step_px` along it. Open chains repeat their
//! end points as the outer control points; closed ones wrap. tension in [-1, 1] (0:
//! Catmull-Rom, 1: straight lines), step_px > 0.
//! `depth`, when given, receives the window depth at each point (linear along each span).
std::vector<glm::dvec2> cardinalSpline(const Chain& chain, double tension, double step_px,
                                       std::vector<double>* depth = nullptr);

}  // namespace shanshui::strokes
