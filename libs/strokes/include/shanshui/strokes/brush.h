// The brush along a stroke (seed 002 §3.4-3.5): a pressure curve per style, and the strip
// of the bristle footprint swept along the Cardinal spline, its width following the
// pressure, for the renderer to fill with ink.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace shanshui::strokes {

//! The thesis's five baimiao line styles and their mix, by how the line's weight changes.
enum class StrokeStyle {
  None,     //!< no strokes
  Qinxian,  //!< 琴弦描 "zither string": even pressure, thin and steady
  Liuye,    //!< 柳葉描 "willow leaf": pressure 0 → 1 → 0, the turn at a seeded random point
  Zaohe,    //!< 棗核描 "date pit": the stroke cut into equal parts, each a quick 0 → 1 → 0
  Jianbi,   //!< 減筆描 "reduced stroke": pressed at once, lifted quickly (1 → 0), centre tip
  Zhuye,    //!< 竹葉描 "bamboo leaf": as jianbi, with the side of the brush (side tip)
  Mixed,    //!< by the stroke's length: long → liuye, middle → zaohe, short → jianbi
};

struct BrushOptions {
  double width_px = 4.0;         //!< full-pressure width, (0, 256]
  double min_pressure = 0.15;    //!< the brush never leaves the paper: width at pressure 0, [0, 1]
  double zaohe_beat_px = 30.0;   //!< date pit: length of one 0 → 1 → 0 beat, (0, inf)
  double mixed_long_px = 120.0;  //!< mixed: liuye at or above this length
  double mixed_short_px = 40.0;  //!< mixed: jianbi below this length, zaohe between
};

//! The style a stroke of this length is drawn in (Mixed resolves by length, others stay).
StrokeStyle styleFor(StrokeStyle style, double length_px, const BrushOptions& options);

//! Pressure in [0, 1] at arc-length fraction t in [0, 1] of a stroke `length_px` long;
//! `seed` varies the willow leaf's turn from stroke to stroke (deterministically).
double pressure(StrokeStyle style, double t, double length_px, std::uint64_t seed, const BrushOptions& options);

//! How much ink a stroke `length_px` long keeps: a painter leaves out short scratches, so
//! strokes under `short_px` are not drawn and the ink rises smoothly to full at three times
//! that length. 1 for any length when short_px ≤ 0.
double lengthInk(double length_px, double short_px);

//! One side of the strip at a spline point.
struct StripVertex {
  glm::dvec2 position;  //!< pixels
  float along = 0;      //!< arc length from the start, pixels
  float across = 0;     //!< -1 on the right edge, +1 on the left
  float pressure = 0;
};

//! The swept footprint as a triangle strip (two vertices per spline point, right then
//! left). Centre tip: symmetric about the path; side tip (Zhuye): the path runs along the
//! brush's heel, a fifth of the width from the right edge. Width = width_px ·
//! (min_pressure + (1 − min_pressure) · pressure).
std::vector<StripVertex> strokeStrip(const std::vector<glm::dvec2>& path, StrokeStyle style, std::uint64_t seed,
                                     const BrushOptions& options);

}  // namespace shanshui::strokes
