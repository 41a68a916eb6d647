// Distortion of a UV parameterization (SPEC.md section 5): Sander et al. 2001 stretch and
// the angle and area distortion, all weighted by surface area, 1 (or 0 for area) = ideal.
#pragma once

#include <string>

#include "shanshui/mesh/mesh.h"

namespace shanshui::param {

//! Singular values σ1 >= σ2 of each triangle's map from UV to the surface, after the UVs are
//! scaled so that their total area equals the surface area (so the metrics ignore scale).
struct Distortion {
  double l2_stretch = 0.0;        //!< sqrt(Σ A (σ1² + σ2²)/2 / Σ A); 1 = isometric
  double linf_stretch = 0.0;      //!< max σ1
  double angle_distortion = 0.0;  //!< area-weighted mean σ1/σ2; 1 = conformal
  double area_distortion = 0.0;   //!< area-weighted mean |log σ1σ2|; 0 = area preserving
  int faces = 0;
  int flipped = 0;     //!< UV orientation opposite to the majority (by area)
  int degenerate = 0;  //!< UV area <= 1e-12 of the mean, or a zero-area surface face
  int non_finite = 0;  //!< faces with a NaN or infinite UV

  //! Finite, one-to-one on every face: no flipped, degenerate or non-finite faces.
  bool valid() const { return faces > 0 && flipped == 0 && degenerate == 0 && non_finite == 0; }
  std::string summary() const;
};

//! Measures mesh.uvs (one per vertex). The mesh must have UVs.
Distortion measureDistortion(const mesh::Mesh& mesh);

}  // namespace shanshui::param
