// OpenMP granularity: loops shorter than this run on the calling thread. A parallel region costs
// a fork/join barrier (microseconds, far more when the cores are shared), which dwarfs the work of
// a few thousand cheap iterations; the CG loop opens several regions per iteration.
#pragma once

#include <cstddef>

namespace serosa::fem {

/// Minimum loop length (rows, nodes, tets) worth a parallel region.
inline constexpr std::ptrdiff_t kParallelMin = 1024;

}  // namespace serosa::fem
