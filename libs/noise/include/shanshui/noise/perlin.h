// Improved Perlin noise (Perlin 2002): the rice-paper canvas of seed 001 (SPEC.md
// section 8). CPU reference in double; shaders/ carries the GLSL version (issue 7).
#pragma once

namespace shanshui::noise {

//! Gradient noise in [-1, 1] with the quintic fade 6t⁵ − 15t⁴ + 10t³ and the 256-entry
//! permutation of the 2002 reference, so published values are reproduced exactly:
//! perlin(3.14, 42, 7) = 0.13691995878400012. Periodic with period 256 in each axis.
double perlin(double x, double y, double z);

//! The fade curve, 6t⁵ − 15t⁴ + 10t³.
double perlinFade(double t);

}  // namespace shanshui::noise
