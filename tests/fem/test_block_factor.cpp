// fem/block_factor.h: the node-blocked single-precision solves of a CHOLMOD factor (supernodal
// L L^T, exported as LDL^T), against CHOLMOD's own solve, on random sparse SPD systems of 3x3
// blocks (a mesh's shape).
#include "fem/block_factor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "engine/math.h"
#include "fem/cholmod_solver.h"
#include "fem/csr_matrix.h"

namespace serosa::fem {
namespace {

// A = m I + sum over random node pairs (i, j) of [S -S; -S S], S = C C^T for a random 3x3 C: a
// mass matrix plus springs, SPD, with the 3x3 block pattern of a mesh's system. Stiffness scales
// spread over `decades` orders of magnitude (stiff contrasts).
CsrMatrix random_system(std::mt19937& rng, int nodes, int pairs, double decades) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, nodes - 1);
  std::map<std::pair<int, int>, Mat3> blocks;
  for (int i = 0; i < nodes; ++i) blocks[{i, i}] = 0.1 * Mat3::Identity();
  for (int k = 0; k < pairs; ++k) {
    const int i = pick(rng), j = pick(rng);
    if (i == j) continue;
    Mat3 c;
    for (int e = 0; e < 9; ++e) c(e / 3, e % 3) = u(rng);
    const Mat3 s = std::pow(10.0, decades * 0.5 * (u(rng) + 1.0)) * c * c.transpose();
    blocks[{i, i}] += s;
    blocks[{j, j}] += s;
    // Eigen leaves a default-constructed block uninitialized: a new one starts at zero.
    blocks.try_emplace({i, j}, Mat3::Zero()).first->second -= s;
    blocks.try_emplace({j, i}, Mat3::Zero()).first->second -= s;
  }
  CsrMatrix a;
  a.rows = 3 * nodes;
  a.row_start.push_back(0);
  for (int i = 0; i < nodes; ++i)
    for (int r = 0; r < 3; ++r) {
      for (auto it = blocks.lower_bound({i, 0}); it != blocks.end() && it->first.first == i; ++it)
        for (int c = 0; c < 3; ++c) {
          a.col.push_back(3 * it->first.second + c);
          a.val.push_back(it->second(r, c));
        }
      a.row_nz.push_back(static_cast<std::int32_t>(a.col.size()) - a.row_start.back());
      a.row_start.push_back(static_cast<std::int32_t>(a.col.size()));
    }
  return a;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

// CHOLMOD's node-blocked factor of a, exported.
bool factor(const CsrMatrix& a, CholmodSolver& chol, LdlFactor& ldl) {
  return chol.analyze(a) && chol.factorize(a) && chol.export_ldl(ldl);
}

TEST(BlockFactor, SolvesAsCholmodDoesToSinglePrecision) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int nodes = 2 + trial % 60;
    const CsrMatrix a = random_system(rng, nodes, 3 * nodes, trial % 3 == 0 ? 4.0 : 1.0);
    CholmodSolver chol(CholmodSolver::Layout::node_blocks);
    LdlFactor ldl;
    ASSERT_TRUE(factor(a, chol, ldl));
    BlockFactor blocks;
    ASSERT_TRUE(blocks.build(ldl)) << "trial " << trial;
    ASSERT_EQ(blocks.rows(), a.rows);
    std::vector<double> b(static_cast<std::size_t>(a.rows)), x(b.size()), y(b.size()), ay(b.size());
    for (double& v : b) v = u(rng);
    chol.solve(b, x);
    blocks.solve(b, y);
    std::vector<double> diff(b.size());
    for (std::size_t i = 0; i < b.size(); ++i) diff[i] = y[i] - x[i];
    // float factor and float sums: a few thousand float roundings of the solution's scale
    EXPECT_LE(max_abs(diff), 1e-3 * max_abs(x)) << "trial " << trial;
    // and it is a solve of A: the residual of y is small against b
    multiply(a, y, ay);
    for (std::size_t i = 0; i < b.size(); ++i) ay[i] -= b[i];
    if (trial % 3 != 0) {
      EXPECT_LE(max_abs(ay), 1e-3 * max_abs(b)) << "trial " << trial;
    }
  }
}

// The node-blocked factor is supernodal L L^T exported as LDL^T: L D L^T must give back P A P^T
// (dense check, to double rounding), with D > 0 and no exact zero (a relaxed supernode's padding)
// among the exported entries.
TEST(BlockFactor, TheExportedFactorRebuildsThePermutedMatrix) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 200; ++trial) {
    const int nodes = 2 + trial % 40;
    const CsrMatrix a = random_system(rng, nodes, 3 * nodes, trial % 3 == 0 ? 4.0 : 1.0);
    CholmodSolver chol(CholmodSolver::Layout::node_blocks);
    LdlFactor ldl;
    ASSERT_TRUE(factor(a, chol, ldl));
    const auto n = static_cast<Eigen::Index>(a.rows);
    Eigen::MatrixXd l = Eigen::MatrixXd::Identity(n, n), pap(n, n);
    for (Eigen::Index j = 0; j < n; ++j)
      for (auto e = static_cast<std::size_t>(ldl.col_start[static_cast<std::size_t>(j)]);
           e < static_cast<std::size_t>(ldl.col_start[static_cast<std::size_t>(j) + 1]); ++e) {
        ASSERT_GT(ldl.row[e], j) << "trial " << trial;
        ASSERT_NE(ldl.val[e], 0.0) << "trial " << trial;
        l(ldl.row[e], j) = ldl.val[e];
      }
    std::vector<double> col(static_cast<std::size_t>(n)), acol(col.size());
    for (Eigen::Index j = 0; j < n; ++j) {  // column j of P A P^T = P A e_perm[j]
      ASSERT_GT(ldl.d[static_cast<std::size_t>(j)], 0.0);
      std::fill(col.begin(), col.end(), 0.0);
      col[static_cast<std::size_t>(ldl.perm[static_cast<std::size_t>(j)])] = 1.0;
      multiply(a, col, acol);
      for (Eigen::Index i = 0; i < n; ++i)
        pap(i, j) = acol[static_cast<std::size_t>(ldl.perm[static_cast<std::size_t>(i)])];
    }
    const Eigen::VectorXd d = Eigen::Map<const Eigen::VectorXd>(ldl.d.data(), n);
    const Eigen::MatrixXd back = l * d.asDiagonal() * l.transpose();
    EXPECT_LE((back - pap).cwiseAbs().maxCoeff(), 1e-10 * pap.cwiseAbs().maxCoeff())
        << "trial " << trial;
  }
}

TEST(BlockFactor, RefusesAFactorThatSplitsANodeOrHasNoPositivePivot) {
  std::mt19937 rng(9);
  const CsrMatrix a = random_system(rng, 20, 60, 1.0);
  CholmodSolver chol(CholmodSolver::Layout::node_blocks);
  LdlFactor ldl;
  ASSERT_TRUE(factor(a, chol, ldl));
  BlockFactor blocks;
  LdlFactor split = ldl;
  std::swap(split.perm[0], split.perm[split.perm.size() - 1]);  // node 0's rows apart
  EXPECT_FALSE(blocks.build(split));
  EXPECT_TRUE(blocks.empty());
  LdlFactor negative = ldl;
  negative.d[7] = -1.0;
  EXPECT_FALSE(blocks.build(negative));
  EXPECT_TRUE(blocks.empty());
  LdlFactor odd = ldl;
  odd.perm.pop_back();
  EXPECT_FALSE(blocks.build(odd));
  EXPECT_TRUE(blocks.build(ldl));
}

// The node-blocked layout orders whole nodes: each node's three rows stay together, in order.
TEST(BlockFactor, TheNodeOrderingKeepsEachNodesRowsTogether) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 50; ++trial) {
    const CsrMatrix a = random_system(rng, 10 + trial, 40 + 3 * trial, 2.0);
    CholmodSolver chol(CholmodSolver::Layout::node_blocks);
    LdlFactor ldl;
    ASSERT_TRUE(factor(a, chol, ldl));
    for (std::size_t k = 0; k < ldl.perm.size(); k += 3) {
      ASSERT_EQ(ldl.perm[k] % 3, 0);
      ASSERT_EQ(ldl.perm[k + 1], ldl.perm[k] + 1);
      ASSERT_EQ(ldl.perm[k + 2], ldl.perm[k] + 2);
    }
  }
}

}  // namespace
}  // namespace serosa::fem
