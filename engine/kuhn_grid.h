// A structured block of tets for benchmarks and tests: a lattice of boxes, each split into the 6
// Kuhn tets around its main diagonal (6 per cell, conforming across cells).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "engine/tet_mesh.h"

namespace serosa {

/// How a Kuhn grid numbers its nodes; its cells (6 consecutive tets each) come in the same order.
enum class KuhnOrder : std::uint8_t {
  kZFastest,  ///< node (i, j, k) has id (i (ny + 1) + j) (nz + 1) + k
  kXFastest,  ///< node (i, j, k) has id i + (nx + 1) (j + (ny + 1) k)
};

/// A block of nx x ny x nz cells on the lattice xs x ys x zs.
struct KuhnGridSpec {
  std::vector<double> xs, ys, zs;  ///< (nx + 1), (ny + 1), (nz + 1) node coordinates, m, increasing
  KuhnOrder order = KuhnOrder::kZFastest;
  /// Group of the tets of cell (i, j, k); group 1 everywhere when empty.
  std::function<std::uint16_t(int i, int j, int k)> group;
};

/// The block of `spec`. Tets are positively oriented at rest: each cell's 6 tets are the paths
/// from its corner (i, j, k) to (i + 1, j + 1, k + 1) along the axes in the orders xyz, xzy, yxz,
/// yzx, zxy, zyx, with the last two nodes swapped where that path is negatively oriented.
/// @throws std::invalid_argument for an axis with fewer than 2 coordinates, or coordinates that
///         are not finite and strictly increasing
[[nodiscard]] TetMesh kuhn_grid(const KuhnGridSpec& spec);

/// `count` + 1 coordinates from `origin` with step h: origin + i h, m.
[[nodiscard]] std::vector<double> kuhn_axis(int count, double h, double origin = 0.0);

/// The cube [0, n h]³ (kZFastest). Group 1 everywhere, or, with `two_groups`, group 1 for cells
/// with i < n / 2 (the lower x half) and group 2 for the rest.
/// @throws std::invalid_argument for n < 1 or h not positive and finite
[[nodiscard]] TetMesh kuhn_grid(int n, double h, bool two_groups = false);

}  // namespace serosa
