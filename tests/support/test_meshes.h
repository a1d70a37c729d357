// The structured test meshes every test folder shares, all built on engine's Kuhn grid
// (engine/kuhn_grid.h): boxes of cubes, each split into the 6 Kuhn tets around its main diagonal
// (conforming across cubes, positively oriented), in the two node numberings the tests use.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "engine/tet_mesh.h"

namespace serosa::test_meshes {

/// nx x ny x nz cubes of edge h (m) from the origin; node (i, j, k) has id
/// (i (ny + 1) + j) (nz + 1) + k. Group 1 + groups * i / nx for cube column i: `groups` slabs
/// along x.
[[nodiscard]] TetMesh kuhn_box(int nx, int ny, int nz, int groups = 1, double h = 0.01);

/// The cube [0, k h]^3 of k^3 cubes (kuhn_box(k, k, k, 2, h): group 1 for cube columns with
/// 2 i < k, else 2). Interior nodes are moved by up to jitter * h in each coordinate, uniformly
/// from a generator seeded with `seed`, in node order (0: the exact grid, with many exactly
/// coplanar nodes); tets are re-oriented after the move.
[[nodiscard]] TetMesh kuhn_cube(int k, double h = 1.0, double jitter = 0.0, std::uint32_t seed = 1);

/// Nodes on the lattice xs x ys x zs (m, strictly increasing), node (i, j, k) has id
/// i + nx (j + ny k) for nx = xs.size(), ny = ys.size(). Group 1 + i % groups for cube column i.
[[nodiscard]] TetMesh kuhn_lattice(const std::vector<double>& xs, const std::vector<double>& ys,
                                   const std::vector<double>& zs, int groups = 1);

/// kuhn_lattice of nx x ny x nz boxes of hx x hy x hz (m) from the origin, group 1.
[[nodiscard]] TetMesh kuhn_bar(int nx, int ny, int nz, double hx, double hy, double hz);

/// k + 1 strictly increasing coordinates from 0 to `size` (m), with random (seeded) spacing.
[[nodiscard]] std::vector<double> random_spacing(std::mt19937& rng, int k, double size);

}  // namespace serosa::test_meshes
