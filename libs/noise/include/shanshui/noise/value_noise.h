// Value noise for the shading's erosion (seed 001 Eq. 3) and the paper's absorbency when
// no canvas is drawn: a tileable texture made once per seed and sampled by the shaders.
#pragma once

#include <cstdint>

#include "shanshui/image/image.h"

namespace shanshui::noise {

//! Coarsest erosion-noise cells per texture tile; the scene's shading.noise_scale is the
//! size of one such cell on the object.
constexpr int kErosionCells = 4;

//! The erosion and added noise of the shading (two channels, tileable, values in [0, 1]):
//! value noise with three octaves on a periodic lattice, the same for the same seed.
image::Image erosionNoise(int size, std::uint64_t seed);
//! Its first channel alone (the erosion's coarse noise), at half the work.
image::Image erosionNoiseCoarse(int size, std::uint64_t seed);

}  // namespace shanshui::noise
