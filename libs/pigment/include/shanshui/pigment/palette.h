// The painter's palette of Chinese landscape painting as Kubelka–Munk pigments: the
// colours of a unit layer on white and on black. The values are chosen by eye to match
// swatches of each pigment (transparent plant colours nearly vanish on black; the mineral
// blues and greens are opaque and stay bright on it); `custom` takes the scene's own pair.
#pragma once

#include <string>
#include <vector>

#include "shanshui/pigment/kubelka_munk.h"

namespace shanshui::pigment {

struct NamedPigment {
  const char* name;
  const char* what;  //!< the pigment, for --describe and the viewer
  Pigment pigment;
};

//! Every named pigment: ochre, indigo, azurite, malachite, cinnabar, gamboge, ink.
const std::vector<NamedPigment>& palette();

//! The pigment of that name; throws naming it and the names there are.
const Pigment& named(const std::string& name);

}  // namespace shanshui::pigment
