// The atmosphere and the dissolving border on the CPU, for marks drawn from points the
// passes know (brush strokes, elements) rather than from the G-buffer: what
// shaders/ink/ink_surface.glsl's presence() leaves of the ink at a world point, with its noise
// at its mean (a mark is small; the surface beside it carries the noise).
#pragma once

#include <glm/glm.hpp>

#include "shanshui/render/render_pass.h"

namespace shanshui::render {

//! The distance fade's range from the frame's eye, as the ink pass sets it: the distances
//! of the scene's nearest and farthest bounding-box corners.
glm::dvec2 fadeRange(const FrameInputs& in);

//! How much of object `object`'s ink at `world` stands against the paper, in [0, 1]: the
//! distance fade, the mist and the border. `to_model` takes world to the object's uploaded
//! coordinates (the inverse of in.modelAt(object)).
double presence(const FrameInputs& in, std::size_t object, const glm::dmat4& to_model, glm::dvec3 world,
                glm::dvec2 fade_range);

//! The picture's horizontal laid flat in the world: the camera's right vector in world x and
//! y (z = 0), unit; +x when the camera looks straight down its right vector.
glm::vec3 pictureHorizontal(const FrameInputs& in);

//! The world z of the scene's water surface (water.level over the frame's world bounds, as
//! the mist's heights are measured), or the lowest float when the scene has no water.
float waterLevel(const FrameInputs& in);

}  // namespace shanshui::render
