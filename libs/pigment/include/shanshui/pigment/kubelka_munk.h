// Kubelka–Munk pigment layers (seed 003 §4.3; the formulas are Curtis et al. 1997 §5.1).
// A pigment is given as two colours of a unit-thickness layer: over white and over black.
// From them come per channel the scattering S and absorption K, and for a layer of any
// thickness its reflectance R and transmittance T. Layers stack (top over bottom) and lie
// on a substrate of known reflectance (paper, or the picture painted so far).
#pragma once

#include <glm/glm.hpp>

namespace shanshui::pigment {

//! A pigment by how a layer of unit thickness looks: each channel in (0, 1), on black
//! darker than on white (a pigment that hides black completely would need R = ∞ thickness).
struct Pigment {
  glm::dvec3 on_white{0.5};
  glm::dvec3 on_black{0.1};
};

//! Per channel: S (scattering per unit thickness) and the model's a = (S + K) / S and
//! b = √(a² − 1), all the GPU needs for a layer of any thickness.
struct Coefficients {
  glm::dvec3 S{0.0}, K{0.0};
  glm::dvec3 a{1.0}, b{0.0};
};

//! Throws naming `what`, the channel and the value when a colour is outside (0, 1) or on
//! black is not darker than on white.
Coefficients coefficients(const Pigment& p, const char* what = "pigment");

//! A layer's reflectance (seen from above and from below) and transmittance per channel.
//! One pigment's layer looks the same from both sides; a stack of different pigments does
//! not, and composition keeps both so that it stays associative. The empty layer reflects
//! nothing and lets everything through.
struct Layer {
  glm::dvec3 R{0.0};        //!< from above
  glm::dvec3 R_below{0.0};  //!< from below
  glm::dvec3 T{1.0};        //!< either way
};

//! A layer `thickness` thick (≥ 0; units of the pigment's unit layer). Finite for any
//! thickness: it tends to the pigment's R∞ = a − b and T = 0.
Layer layer(const Coefficients& c, double thickness);

//! `top` laid over `bottom` (the Kubelka–Munk composition; associative).
Layer over(const Layer& top, const Layer& bottom);

//! What the eye sees of `l` lying on a substrate of reflectance `substrate` (each in [0, 1]).
glm::dvec3 onSubstrate(const Layer& l, glm::dvec3 substrate);

}  // namespace shanshui::pigment
