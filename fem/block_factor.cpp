#include "fem/block_factor.h"

#include <algorithm>
#include <array>
#include <cstddef>

namespace serosa::fem {

void BlockFactor::clear() {
  m_nodes = 0;
  m_node_of.clear();
  m_diag.clear();
  m_block_start.clear();
  m_block_row.clear();
  m_block.clear();
}

namespace {

// The permutation keeps each node's rows together, in order: perm[3k + c] = 3 node + c.
bool node_blocked(const LdlFactor& f, std::vector<std::int32_t>& node_of) {
  const auto rows = f.perm.size();
  if (rows % 3 != 0 || f.col_start.size() != rows + 1 || f.d.size() != rows) return false;
  node_of.resize(rows / 3);
  for (std::size_t k = 0; k < rows / 3; ++k) {
    const std::int32_t p = f.perm[3 * k];
    if (p % 3 != 0 || f.perm[3 * k + 1] != p + 1 || f.perm[3 * k + 2] != p + 2) return false;
    node_of[k] = p / 3;
  }
  return true;
}

}  // namespace

bool BlockFactor::build(const LdlFactor& f) {
  clear();
  if (!node_blocked(f, m_node_of)) return false;
  const auto nodes = static_cast<std::int32_t>(m_node_of.size());
  m_diag.assign(6 * static_cast<std::size_t>(nodes), 0.0f);
  m_block_start.assign(static_cast<std::size_t>(nodes) + 1, 0);
  std::vector<std::int32_t> slot(static_cast<std::size_t>(nodes), -1);  // node -> block this col
  for (std::int32_t k = 0; k < nodes; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    const auto first = static_cast<std::int32_t>(m_block_row.size());
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t j = 3 * uk + c;
      if (!(f.d[j] > 0.0)) {
        clear();
        return false;
      }
      m_diag[6 * uk + 3 + c] = static_cast<float>(1.0 / f.d[j]);
      for (auto e = static_cast<std::size_t>(f.col_start[j]);
           e < static_cast<std::size_t>(f.col_start[j + 1]); ++e) {
        const auto r = static_cast<std::size_t>(f.row[e]);
        const std::size_t node = r / 3, rc = r % 3;
        if (node == uk) {  // inside the diagonal block: (1,0), (2,0), (2,1)
          if (rc <= c) continue;
          m_diag[6 * uk + (c == 0 ? rc - 1 : 2)] = static_cast<float>(f.val[e]);
          continue;
        }
        std::int32_t& s = slot[node];
        if (s < first) {
          s = static_cast<std::int32_t>(m_block_row.size());
          m_block_row.push_back(static_cast<std::int32_t>(node));
          m_block.resize(m_block.size() + 9, 0.0f);
        }
        m_block[9 * static_cast<std::size_t>(s) + 3 * rc + c] = static_cast<float>(f.val[e]);
      }
    }
    m_block_start[uk + 1] = static_cast<std::int32_t>(m_block_row.size());
  }
  m_nodes = nodes;
  m_y.resize(3 * static_cast<std::size_t>(nodes));
  return true;
}

void BlockFactor::solve(std::span<const double> b, std::span<double> x) {
  const auto n = static_cast<std::size_t>(m_nodes);
  float* y = m_y.data();
  for (std::size_t k = 0; k < n; ++k) {
    const double* bk = b.data() + 3 * static_cast<std::size_t>(m_node_of[k]);
    y[3 * k] = static_cast<float>(bk[0]);
    y[3 * k + 1] = static_cast<float>(bk[1]);
    y[3 * k + 2] = static_cast<float>(bk[2]);
  }
  // L y = b: the diagonal block's unit lower triangle, then the blocks below it.
  for (std::size_t k = 0; k < n; ++k) {
    const float* dk = m_diag.data() + 6 * k;
    float* yk = y + 3 * k;
    yk[1] -= dk[0] * yk[0];
    yk[2] -= dk[1] * yk[0] + dk[2] * yk[1];
    const float y0 = yk[0], y1 = yk[1], y2 = yk[2];
    for (auto s = static_cast<std::size_t>(m_block_start[k]);
         s < static_cast<std::size_t>(m_block_start[k + 1]); ++s) {
      const float* l = m_block.data() + 9 * s;
      float* yi = y + 3 * static_cast<std::size_t>(m_block_row[s]);
      yi[0] -= l[0] * y0 + l[1] * y1 + l[2] * y2;
      yi[1] -= l[3] * y0 + l[4] * y1 + l[5] * y2;
      yi[2] -= l[6] * y0 + l[7] * y1 + l[8] * y2;
    }
  }
  // D, then L^T x = y: the blocks below first, then the diagonal block's unit upper triangle.
  for (std::size_t k = n; k-- > 0;) {
    const float* dk = m_diag.data() + 6 * k;
    float* yk = y + 3 * k;
    float s0 = yk[0] * dk[3], s1 = yk[1] * dk[4], s2 = yk[2] * dk[5];
    for (auto s = static_cast<std::size_t>(m_block_start[k]);
         s < static_cast<std::size_t>(m_block_start[k + 1]); ++s) {
      const float* l = m_block.data() + 9 * s;
      const float* yi = y + 3 * static_cast<std::size_t>(m_block_row[s]);
      s0 -= l[0] * yi[0] + l[3] * yi[1] + l[6] * yi[2];
      s1 -= l[1] * yi[0] + l[4] * yi[1] + l[7] * yi[2];
      s2 -= l[2] * yi[0] + l[5] * yi[1] + l[8] * yi[2];
    }
    s1 -= dk[2] * s2;
    s0 -= dk[0] * s1 + dk[1] * s2;
    yk[0] = s0;
    yk[1] = s1;
    yk[2] = s2;
  }
  for (std::size_t k = 0; k < n; ++k) {
    double* xk = x.data() + 3 * static_cast<std::size_t>(m_node_of[k]);
    xk[0] = static_cast<double>(y[3 * k]);
    xk[1] = static_cast<double>(y[3 * k + 1]);
    xk[2] = static_cast<double>(y[3 * k + 2]);
  }
}

}  // namespace serosa::fem
