// OpenMP granularity: loops shorter than this run on the calling thread. A parallel region costs
// a fork/join barrier (microseconds, far more when the cores are shared), which dwarfs the work of
// a few thousand cheap iterations; the CG loop opens several regions per iteration.
#pragma once

#include <array>
#include <cstddef>

namespace serosa::fem {

/// Minimum loop length (rows, nodes, tets) worth a parallel region.
inline constexpr std::ptrdiff_t kParallelMin = 1024;

/// Fixed number of chunks of the deterministic reductions: sums do not depend on the thread count.
inline constexpr int kChunks = 64;

/// Runs body(lo, hi, sums) over kChunks fixed chunks of [0, n) (in parallel when n is large) and
/// returns the K per-chunk sums added in chunk order: the same bits for any OpenMP thread count
/// (replays stay exact).
template <int K, class Body>
std::array<double, K> chunked(std::ptrdiff_t n, const Body& body) {
  std::array<std::array<double, K>, kChunks> part{};
#pragma omp parallel for schedule(static) if (n >= kParallelMin)
  for (int c = 0; c < kChunks; ++c) {
    std::array<double, K> s{};
    body(n * c / kChunks, n * (c + 1) / kChunks, s);
    part[static_cast<std::size_t>(c)] = s;
  }
  std::array<double, K> total{};
  for (const auto& p : part)
    for (std::size_t k = 0; k < static_cast<std::size_t>(K); ++k) total[k] += p[k];
  return total;
}

}  // namespace serosa::fem
