// fem/system_matrix.h: the matrix-free operator, the blocked SpMV and the generic CSR product all
// apply the same A (with fixed nodes, random rotations and a stiffness contrast), and the
// Newton rotation extraction agrees with the SVD polar factor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "fem/block_system.h"
#include "fem/fem_elements.h"
#include "fem/pcg.h"
#include "fem/rotation.h"
#include "fem/system_matrix.h"
#include "fem_fixtures.h"

namespace serosa::fem {
namespace {

// A jittered Kuhn bar clamped at x = 0, a third of its tets a million times stiffer than the
// rest, every tet turned by a random rotation: its elements, system pattern and rotated gradients.
struct TurnedBar {
  TetMesh mesh;
  FemElements el;
  SystemPattern pat;
  CsrMatrix a;
  std::vector<Vec3> rg;  // (4 tets)
};

TurnedBar turned_bar(std::mt19937& rng, int jitter_seed) {
  TurnedBar b{test_meshes::kuhn_bar(5, 3, 2, 0.1, 0.1, 0.1), {}, {}, {}, {}};
  TetMesh& m = b.mesh;
  fixtures::jitter_interior(m, 0, 0.5, 0, 0.3, 0, 0.2, 0.02, jitter_seed);
  m.fill_node_state();
  for (std::size_t i = 0; i < m.rest.size(); ++i) m.fixed[i] = m.rest[i].x() < 1e-9 ? 1 : 0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) m.group[t] = t % 3 == 0 ? 2 : 1;
  FemConfig cfg;
  cfg.materials[1] = FemMaterial{3000.0, 0.45, 1000.0, 0.1, 0.1};
  cfg.materials[2] = FemMaterial{3e9, 0.3, 2000.0, 0.0, 0.01};
  build_elements(m, cfg, b.el);
  build_pattern(m, b.pat, b.a);
  std::vector<Mat3> rot(m.tets.size());
  for (Mat3& r : rot) r = fixtures::random_rotation(rng);
  b.rg.resize(4 * m.tets.size());
  rotated_gradients(b.el, rot, b.rg);
  return b;
}

TEST(SystemOperator, MatrixFreeEqualsAssembledAndBlockedSpmv) {
  std::mt19937 rng(3);
  TurnedBar bar = turned_bar(rng, 4);
  TetMesh& m = bar.mesh;
  FemElements& el = bar.el;
  SystemPattern& pat = bar.pat;
  CsrMatrix& a = bar.a;
  std::vector<Vec3>& rg = bar.rg;
  const double dt = 0.01;
  fill_system(m, el, pat, rg, dt, a);
  SystemOperator op;
  prepare_operator(m, el, dt, op);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto n3 = static_cast<std::size_t>(a.rows);
  std::vector<double> x(n3), y1(n3), y2(n3), y3(n3), inv(n3);
  for (int trial = 0; trial < 5; ++trial) {
    for (double& v : x) v = u(rng);
    multiply(a, x, y1);
    multiply_system(pat, a, x, y2);
    apply_operator(m, el, pat, rg, op, x, y3);
    double scale = 0.0;
    for (double v : y1) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < n3; ++i) {
      EXPECT_NEAR(y2[i], y1[i], 1e-12 * scale);
      EXPECT_NEAR(y3[i], y1[i], 1e-12 * scale);
    }
  }
  operator_inverse_diagonal(el, pat, rg, op, inv);
  for (std::int32_t r = 0; r < a.rows; ++r)
    for (std::int32_t k = a.row_start[static_cast<std::size_t>(r)];
         k < a.row_start[static_cast<std::size_t>(r)] + a.row_nz[static_cast<std::size_t>(r)]; ++k)
      if (a.col[static_cast<std::size_t>(k)] == r) {
        EXPECT_NEAR(1.0 / inv[static_cast<std::size_t>(r)], a.val[static_cast<std::size_t>(k)],
                    1e-12 * a.val[static_cast<std::size_t>(k)]);
      }
}

// Block storage (fem/block_system.h): the same matrix as fill_system() in double, entry by entry;
// the same product and diagonal; in float every entry within float rounding (2^-24 relative) and
// the product within that of the row sums of |A| |x|.
TEST(BlockSystem, EqualsCsrFillInDoubleAndRoundsOnlyTheEntriesInFloat) {
  std::mt19937 rng(5);
  TurnedBar bar = turned_bar(rng, 6);
  TetMesh& m = bar.mesh;
  FemElements& el = bar.el;
  SystemPattern& pat = bar.pat;
  CsrMatrix& a = bar.a;
  std::vector<Vec3>& rg = bar.rg;
  fill_system(m, el, pat, rg, 0.01, a);
  std::vector<double> bd(block_storage(pat));
  std::vector<float> bf(block_storage(pat));
  std::vector<TetScale> sc(m.tets.size());
  for (std::size_t t = 0; t < sc.size(); ++t) sc[t] = tet_scale(el.elements[t], 0.01);
  std::vector<double> fill_scratch;
  fill_blocks<double>(m, el, pat, rg, sc, 0.01, bd, fill_scratch);
  fill_blocks<float>(m, el, pat, rg, sc, 0.01, bf, fill_scratch);
  CsrMatrix from_d = a, from_f = a;
  std::fill(from_d.val.begin(), from_d.val.end(), -7.0);
  blocks_to_csr<double>(pat, bd, from_d);
  blocks_to_csr<float>(pat, bf, from_f);
  double scale = 0.0;
  for (double v : a.val) scale = std::max(scale, std::abs(v));
  ASSERT_GT(scale, 0.0);
  for (std::int32_t r = 0; r < a.rows; ++r) {
    const auto ur = static_cast<std::size_t>(r);
    for (std::int32_t k = a.row_start[ur]; k < a.row_start[ur] + a.row_nz[ur]; ++k) {
      const auto uk = static_cast<std::size_t>(k);
      EXPECT_NEAR(from_d.val[uk], a.val[uk], 1e-13 * scale) << "row " << r;
      EXPECT_NEAR(from_f.val[uk], a.val[uk], 6.0e-8 * std::abs(a.val[uk])) << "row " << r;
    }
  }
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto n3 = static_cast<std::size_t>(a.rows);
  std::vector<double> x(n3), y(n3), yd(n3), yf(n3), inv_d(n3), inv_f(n3), absx(n3), bound(n3);
  for (double& v : x) v = u(rng);
  CsrMatrix abs_a = a;
  for (double& v : abs_a.val) v = std::abs(v);
  for (std::size_t i = 0; i < n3; ++i) absx[i] = std::abs(x[i]);
  multiply(a, x, y);
  multiply(abs_a, absx, bound);
  // The product and, in the same pass, x . Ax, for both storages.
  const double xyd = multiply_blocks_dot<double>(pat, bd, x, yd);
  const double xyf = multiply_blocks_dot<float>(pat, bf, x, yf);
  EXPECT_NEAR(xyd, dot(x, yd), 1e-12 * dot(absx, bound));
  EXPECT_NEAR(xyf, dot(x, yf), 1e-12 * dot(absx, bound));
  for (std::size_t i = 0; i < n3; ++i) {
    EXPECT_NEAR(yd[i], y[i], 1e-12 * bound[i]) << i;
    EXPECT_NEAR(yf[i], y[i], 1e-7 * bound[i]) << i;
  }
  blocks_inverse_diagonal<double>(pat, bd, inv_d);
  blocks_inverse_diagonal<float>(pat, bf, inv_f);
  std::vector<double> inv(n3);
  PcgScratch scratch;
  const Preconditioner jac = jacobi(a, scratch);
  for (std::size_t i = 0; i < n3; ++i) {
    EXPECT_NEAR(inv_d[i], jac.inv_diag[i], 1e-14 * jac.inv_diag[i]);
    EXPECT_NEAR(inv_f[i], jac.inv_diag[i], 1e-7 * jac.inv_diag[i]);
  }
}

// The patch after a cut or a grasp fills only its own rows: over random masks, every masked row
// (blocks and CSR) has the full fill's bits, and every other row keeps what it held before.
TEST(BlockSystem, AMaskedFillGivesTheMaskedRowsExactlyAndLeavesTheOthers) {
  std::mt19937 rng(11);
  TurnedBar bar = turned_bar(rng, 3);
  const TetMesh& m = bar.mesh;
  const SystemPattern& pat = bar.pat;
  const CsrMatrix& a = bar.a;
  std::vector<TetScale> sc(m.tets.size());
  for (std::size_t t = 0; t < sc.size(); ++t) sc[t] = tet_scale(bar.el.elements[t], 0.005);
  std::vector<double> full(block_storage(pat)), scratch;
  fill_blocks<double>(m, bar.el, pat, bar.rg, sc, 0.005, full, scratch);
  CsrMatrix full_csr = a;
  blocks_to_csr<double>(pat, full, full_csr);
  std::bernoulli_distribution pick(0.2);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::uint8_t> rows(m.rest.size());
    for (auto& r : rows) r = pick(rng) ? 1 : 0;
    std::vector<double> blocks(full.size(), -3.0);
    CsrMatrix csr = a;
    std::fill(csr.val.begin(), csr.val.end(), -5.0);
    fill_blocks<double>(m, bar.el, pat, bar.rg, sc, 0.005, blocks, scratch, rows);
    blocks_to_csr<double>(pat, blocks, csr, rows);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto b0 = static_cast<std::size_t>(9 * pat.nbr.start[i]);
      const auto len = static_cast<std::size_t>(9 * pat.nbr.count[i]);
      for (std::size_t k = b0; k < b0 + len; ++k)
        ASSERT_EQ(blocks[k], rows[i] != 0 ? full[k] : -3.0) << "node " << i;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t r = 3 * i + c;
        const auto begin = static_cast<std::size_t>(csr.row_start[r]);
        for (std::size_t k = begin; k < begin + static_cast<std::size_t>(csr.row_nz[r]); ++k)
          ASSERT_EQ(csr.val[k], rows[i] != 0 ? full_csr.val[k] : -5.0) << "row " << r;
      }
    }
  }
}

// The lagged factor's copy of A drops the slack between rows and keeps every row's entries.
TEST(CsrMatrix, CopyPackedKeepsEveryRowAndDropsTheSlack) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> len(0, 6), slack(0, 3);
  for (int trial = 0; trial < 100; ++trial) {
    CsrMatrix a;
    a.rows = 1 + trial % 17;
    for (std::int32_t r = 0; r < a.rows; ++r) {
      a.row_start.push_back(static_cast<std::int32_t>(a.col.size()));
      a.row_nz.push_back(len(rng));
      const int room = a.row_nz.back() + slack(rng);
      for (int k = 0; k < room; ++k) {
        a.col.push_back(k);
        a.val.push_back(k < a.row_nz.back() ? 1.0 + r + 0.1 * k : -1.0);
      }
    }
    a.row_start.push_back(static_cast<std::int32_t>(a.col.size()));
    CsrMatrix b;
    copy_packed(a, b);
    ASSERT_EQ(b.rows, a.rows);
    ASSERT_EQ(b.storage(), a.nnz());
    for (std::size_t r = 0; r < static_cast<std::size_t>(a.rows); ++r) {
      ASSERT_EQ(b.row_nz[r], a.row_nz[r]);
      for (std::int32_t k = 0; k < a.row_nz[r]; ++k) {
        ASSERT_EQ(b.col[static_cast<std::size_t>(b.row_start[r] + k)],
                  a.col[static_cast<std::size_t>(a.row_start[r] + k)]);
        ASSERT_EQ(b.val[static_cast<std::size_t>(b.row_start[r] + k)],
                  a.val[static_cast<std::size_t>(a.row_start[r] + k)]);
      }
    }
    ASSERT_EQ(b.row_start.back(), b.storage());
  }
}

TEST(Rotation, NewtonMatchesSvdAndConvergesFastFromAWarmStart) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> s(0.3, 2.0);
  for (int k = 0; k < 500; ++k) {
    const Mat3 rot = fixtures::random_rotation(rng);
    // F = R S with S symmetric positive definite (a stretch in random axes): polar factor R.
    const Mat3 axes = fixtures::random_rotation(rng);
    const Mat3 f = rot * axes * Vec3(s(rng), s(rng), s(rng)).asDiagonal() * axes.transpose();
    Quat q = Quat::Identity();
    EXPECT_TRUE(newton_rotation(f, q, 100));
    EXPECT_LE((q.toRotationMatrix() - polar_rotation_svd(f)).norm(), 1e-8);
    // Warm start 0.05 rad away: Newton needs few iterations (Müller's scalar step needs ~15).
    Quat w(Eigen::AngleAxisd(0.05, Vec3::UnitX()).toRotationMatrix() * rot);
    EXPECT_TRUE(newton_rotation(f, w, 5));
    EXPECT_LE((w.toRotationMatrix() - rot).norm(), 1e-8);
  }
}

}  // namespace
}  // namespace serosa::fem
