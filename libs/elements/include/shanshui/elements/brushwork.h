// The brushwork of an element (issue 44): each kind of tree grown from a seed as a list of
// marks (dabs, pointed strokes, tapering branches) in units of the tree's height, with the
// level of detail each mark belongs to: full brushwork near, a few strokes in the middle
// distance, one dab far. The renderer cross-fades the levels by the tree's size on screen
// (levelWeights), so its ink changes continuously with distance.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "shanshui/elements/placement.h"

namespace shanshui::elements {

//! How a mark's ink is laid between its two ends (shaders/elements/elements.frag draws them).
enum class Shape : std::uint8_t {
  Dab,     //!< a round-ended blot along a → b, edge broken by noise
  Leaf,    //!< pointed at both ends, widest in the middle (needles, leaves, vertical dots)
  Branch,  //!< full width at a, tapering towards b (trunks, branches, twigs)
};

//! Levels of detail, as bits of Mark::levels.
inline constexpr std::uint8_t kFar = 1, kMiddle = 2, kNear = 4;

//! One mark, in units of the element's height: x to the right, y up from its foot.
struct Mark {
  glm::vec2 a{0.0f}, b{0.0f};
  float width = 0.0f;  //!< at its widest, same units
  float ink = 1.0f;    //!< [0, 1]
  Shape shape = Shape::Dab;
  std::uint8_t levels = kFar | kMiddle | kNear;
};

//! The brushwork of one tree of `kind`, grown from `seed`: every level's marks. MossDot gives
//! one dab of unit width at the origin.
std::vector<Mark> growBrushwork(Kind kind, std::uint32_t seed);

//! Heights on screen (pixels at 1024 high) over which the levels cross-fade: far into middle,
//! middle into near. The renderer's expansion shader takes them as a uniform.
inline constexpr std::array<float, 4> kLevelBands{8.0f, 14.0f, 56.0f, 88.0f};

//! Weights of the far, middle and near levels for an element `px` pixels high in a picture
//! 1024 pixels high: the far dab alone below 8 px, fading into the middle strokes up to
//! 14 px, which fade into the full brushwork from 56 to 88 px (where a needle is about a
//! pixel wide). They sum to 1 and change continuously with px.
std::array<float, 3> levelWeights(double px);

}  // namespace shanshui::elements
