// A structured block of tets for benchmarks and tests: n × n × n cubes of edge h, each split into
// the 6 Kuhn tets around its main diagonal (6 n³ tets, (n + 1)³ nodes, conforming).
#pragma once

#include "engine/tet_mesh.h"

namespace serosa {

/// The block [0, n h]³. Tets are positively oriented at rest. Group 1 everywhere, or, with
/// `two_groups`, group 1 for cubes with i < n / 2 (the lower x half) and group 2 for the rest.
/// @throws std::invalid_argument for n < 1 or h not positive and finite
[[nodiscard]] TetMesh kuhn_grid(int n, double h, bool two_groups = false);

}  // namespace serosa
