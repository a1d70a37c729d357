#include "fem/block_system.h"

#include <algorithm>
#include <cstring>
#include <type_traits>
#include <vector>

#include <omp.h>

#include "fem/parallel.h"

namespace serosa::fem {

std::size_t block_storage(const SystemPattern& p) { return 9 * p.nbr.data.size(); }

template <class T>
void fill_blocks(const TetMesh& mesh, const FemElements& el, const SystemPattern& p,
                 std::span<const Vec3> rg, std::span<const TetScale> scale, double dt_s,
                 std::span<T> blocks, std::vector<double>& scratch,
                 std::span<const std::uint8_t> rows) {
  T* out = blocks.data();
  // One slice of the scratch per thread, for one node's blocks (9 per neighbour, summed in
  // double): sized here, so it allocates only when the pattern's widest row or the thread count
  // grows, never in a steady step.
  std::int32_t widest = 0;
  for (std::int32_t i = 0; i < p.nodes; ++i)
    widest = std::max(widest, p.nbr.count[static_cast<std::size_t>(i)]);
  const auto slice = static_cast<std::size_t>(9 * widest);
  const auto threads = static_cast<std::size_t>(omp_get_max_threads());
  if (scratch.size() < threads * slice) scratch.resize(threads * slice);
#pragma omp parallel if (p.nodes >= kParallelMin)
  {
    double* s = scratch.data() + slice * static_cast<std::size_t>(omp_get_thread_num());
#pragma omp for schedule(static)
    for (std::int32_t i = 0; i < p.nodes; ++i) {
      const auto ui = static_cast<std::size_t>(i);
      if (!rows.empty() && rows[ui] == 0) continue;
      const std::int32_t base = 9 * p.nbr.start[ui];
      const auto len = static_cast<std::size_t>(9 * p.nbr.count[ui]);
      // Diagonal block's offset in the node's storage: 9 * (index of i in its neighbour list).
      const auto self = static_cast<std::size_t>(3 * (p.diag_start[ui] - base));
      std::fill(s, s + len, 0.0);
      if (node_constrained(mesh, el, ui)) {
        const double diag = el.node_mass[ui] > 0.0 ? el.node_mass[ui] : 1.0;
        s[self] = s[self + 4] = s[self + 8] = diag;
      } else {
        const double md = el.node_mass[ui] + dt_s * el.node_damping[ui];
        s[self] = s[self + 4] = s[self + 8] = md;
        // (dt^2 + dt beta) V (lambda ra rb^T + mu rb ra^T + mu (ra . rb) I), ra = R b_a.
        const std::span<const std::int32_t> incs = p.incident_of(ui);
        for (std::size_t q = 0; q < incs.size(); ++q) {
          const auto inc = static_cast<std::size_t>(incs[q]);
          if (q + 4 < incs.size()) {  // the fill waits on these scattered per-tet reads
            const auto tn = static_cast<std::size_t>(incs[q + 4]) / 4;
            __builtin_prefetch(&p.block[tn]);
            __builtin_prefetch(&rg[4 * tn]);
            __builtin_prefetch(&rg[4 * tn + 3]);
            __builtin_prefetch(&scale[tn]);
            __builtin_prefetch(&mesh.tets[tn]);
          }
          const std::size_t t = inc / 4;
          const std::size_t ca = inc % 4;
          const auto [sl, sm] = scale[t];
          if (sl == 0.0 && sm == 0.0) continue;  // inactive
          const Vec3& ra = rg[4 * t + ca];
          const double la[3] = {sl * ra.x(), sl * ra.y(), sl * ra.z()};
          const double ma[3] = {sm * ra.x(), sm * ra.y(), sm * ra.z()};
          const Tet& tet = mesh.tets[t];
          // The tet's four blocks (a, b) at once, lane = corner b (vectorizes): entry (r, c) =
          // la_r rb_c + rb_r ma_c (+ ma . rb on the diagonal), kept at r + 3 c (column-major).
          // A constrained b gets rb = 0.
          double b[3][4];
          bool live[4];
          for (std::size_t cb = 0; cb < 4; ++cb) {
            live[cb] = !node_constrained(mesh, el, static_cast<std::size_t>(tet[cb]));
            const Vec3& rb = rg[4 * t + cb];
            for (int k = 0; k < 3; ++k) b[k][cb] = live[cb] ? rb[k] : 0.0;
          }
          double e[9][4];
          for (std::size_t cb = 0; cb < 4; ++cb) {
            const double dd = ma[0] * b[0][cb] + ma[1] * b[1][cb] + ma[2] * b[2][cb];
            for (int r0 = 0; r0 < 3; ++r0)
              for (int c0 = 0; c0 < 3; ++c0)
                e[r0 + 3 * c0][cb] =
                    la[r0] * b[c0][cb] + b[r0][cb] * ma[c0] + (r0 == c0 ? dd : 0.0);
          }
          for (std::size_t cb = 0; cb < 4; ++cb) {
            if (!live[cb]) continue;
            double* blk = s + 3 * static_cast<std::size_t>(p.block[t][4 * ca + cb] - base);
            for (int k = 0; k < 9; ++k) blk[k] += e[k][cb];
          }
        }
      }
      T* dst = out + base;
      for (std::size_t k = 0; k < len; ++k) dst[k] = static_cast<T>(s[k]);
    }
  }
}

// Node i's row of blocks times x: (y0, y1, y2) = sum_k B_k x_{l[k]}, blocks column-major.
template <class T>
inline void block_row(const T* b, const std::int32_t* l, std::int32_t count, const double* xp,
                      double y[3]) {
  if constexpr (std::is_same_v<T, double>) {
    // Rows 0-1 as pairs: each column's first two entries are adjacent (two SSE2 lanes).
    using V2 = double __attribute__((vector_size(16)));
    V2 y01 = {0.0, 0.0};
    double y2 = 0.0;
    for (std::int32_t k = 0; k < count; ++k, b += 9) {
      const double* xb = xp + 3 * static_cast<std::ptrdiff_t>(l[k]);
      V2 c0, c1, c2;
      std::memcpy(&c0, b, sizeof c0);
      std::memcpy(&c1, b + 3, sizeof c1);
      std::memcpy(&c2, b + 6, sizeof c2);
      y01 += c0 * xb[0] + c1 * xb[1] + c2 * xb[2];
      y2 += b[2] * xb[0] + b[5] * xb[1] + b[8] * xb[2];
    }
    y[0] = y01[0];
    y[1] = y01[1];
    y[2] = y2;
  } else {
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (std::int32_t k = 0; k < count; ++k, b += 9) {
      const double* xb = xp + 3 * static_cast<std::ptrdiff_t>(l[k]);
      const double x0 = xb[0], x1 = xb[1], x2 = xb[2];
      y0 += static_cast<double>(b[0]) * x0 + static_cast<double>(b[3]) * x1 +
            static_cast<double>(b[6]) * x2;
      y1 += static_cast<double>(b[1]) * x0 + static_cast<double>(b[4]) * x1 +
            static_cast<double>(b[7]) * x2;
      y2 += static_cast<double>(b[2]) * x0 + static_cast<double>(b[5]) * x1 +
            static_cast<double>(b[8]) * x2;
    }
    y[0] = y0;
    y[1] = y1;
    y[2] = y2;
  }
}

template <class T>
double multiply_blocks_dot(const SystemPattern& p, std::span<const T> blocks,
                           std::span<const double> x, std::span<double> y) {
  const double* xp = x.data();
  double* yp = y.data();
  const T* bp = blocks.data();
  const std::int32_t* nbr = p.nbr.data.data();
  const std::int32_t* start = p.nbr.start.data();
  const std::int32_t* count = p.nbr.count.data();
  return chunked<1>(p.nodes, [&](std::ptrdiff_t lo, std::ptrdiff_t hi, std::array<double, 1>& acc) {
    double xy = 0.0;
    for (std::ptrdiff_t i = lo; i < hi; ++i) {
      const std::int32_t s = start[i];
      double* yi = yp + 3 * i;
      block_row(bp + 9 * static_cast<std::ptrdiff_t>(s), nbr + s, count[i], xp, yi);
      xy += xp[3 * i] * yi[0] + xp[3 * i + 1] * yi[1] + xp[3 * i + 2] * yi[2];
    }
    acc[0] = xy;
  })[0];
}

template <class T>
void blocks_inverse_diagonal(const SystemPattern& p, std::span<const T> blocks,
                             std::span<double> inv_diag) {
#pragma omp parallel for schedule(static) if (p.nodes >= kParallelMin)
  for (std::int32_t i = 0; i < p.nodes; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    const std::int32_t base = 9 * p.nbr.start[ui];
    const auto d = static_cast<std::size_t>(base + 3 * (p.diag_start[ui] - base));
    for (std::size_t c = 0; c < 3; ++c) {
      const auto v = static_cast<double>(blocks[d + 4 * c]);
      inv_diag[3 * ui + c] = v > 0.0 ? 1.0 / v : 1.0;
    }
  }
}

template <class T>
void blocks_to_csr(const SystemPattern& p, std::span<const T> blocks, CsrMatrix& a,
                   std::span<const std::uint8_t> rows) {
  for (std::int32_t i = 0; i < p.nodes; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (!rows.empty() && rows[ui] == 0) continue;
    const auto base = static_cast<std::size_t>(9 * p.nbr.start[ui]);
    const auto cnt = static_cast<std::size_t>(p.nbr.count[ui]);
    const std::size_t len = 3 * cnt;
    for (std::size_t k = 0; k < cnt; ++k)
      for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t c = 0; c < 3; ++c)
          a.val[base + r * len + 3 * k + c] = static_cast<double>(blocks[base + 9 * k + r + 3 * c]);
  }
}

template void fill_blocks<double>(const TetMesh&, const FemElements&, const SystemPattern&,
                                  std::span<const Vec3>, std::span<const TetScale>, double,
                                  std::span<double>, std::vector<double>&,
                                  std::span<const std::uint8_t>);
template void fill_blocks<float>(const TetMesh&, const FemElements&, const SystemPattern&,
                                 std::span<const Vec3>, std::span<const TetScale>, double,
                                 std::span<float>, std::vector<double>&,
                                 std::span<const std::uint8_t>);
template double multiply_blocks_dot<double>(const SystemPattern&, std::span<const double>,
                                            std::span<const double>, std::span<double>);
template double multiply_blocks_dot<float>(const SystemPattern&, std::span<const float>,
                                           std::span<const double>, std::span<double>);
template void blocks_inverse_diagonal<double>(const SystemPattern&, std::span<const double>,
                                              std::span<double>);
template void blocks_inverse_diagonal<float>(const SystemPattern&, std::span<const float>,
                                             std::span<double>);
template void blocks_to_csr<double>(const SystemPattern&, std::span<const double>, CsrMatrix&,
                                    std::span<const std::uint8_t>);
template void blocks_to_csr<float>(const SystemPattern&, std::span<const float>, CsrMatrix&,
                                   std::span<const std::uint8_t>);

}  // namespace serosa::fem
