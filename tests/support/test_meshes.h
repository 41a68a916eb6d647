// Meshes with known geometry for tests: libs/mesh's shapes under the tests' namespace.
#pragma once

#include "shanshui/mesh/shapes.h"

namespace shanshui::test {

using mesh::heightGrid;
using mesh::torus;
using mesh::unitCube;
using mesh::uvSphere;

}  // namespace shanshui::test
