// Scaling UVs after parameterization (SPEC.md section 5, "UV adjustment").
#pragma once

#include "shanshui/mesh/mesh.h"

namespace shanshui::param {

//! Scales the UVs (about their minimum corner, which goes to 0) so that one texture repeat
//! (1 UV unit) covers `world_size` units of surface on average: stroke size no longer
//! depends on mesh size. world_size > 0.
void scaleToTexelSize(mesh::Mesh& mesh, double world_size);

//! Uniform scale and shift into [0, 1]² (the longer side spans [0, 1]).
void normalizeUvs(mesh::Mesh& mesh);

}  // namespace shanshui::param
