// The raw CUDA side of the extraction, defined in surface/extract_surface_cuda.cu when nvcc is
// found (serosa_surface_cuda). Plain arrays only (no Eigen, no TetMesh), so that nvcc compiles no
// Eigen; surface/extract_surface_cuda_entry.cpp wraps it into extract_surface_cuda(TetMesh).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace serosa::surface::detail {

/// The pipeline's output copied back to host memory (shapes as in SurfaceMesh).
struct HostBoundary {
  std::vector<std::array<std::int32_t, 3>> faces;  ///< (f) outward node ids, grouped
  std::vector<std::int32_t> face_tet;              ///< (f)
  std::vector<std::uint16_t> face_group;           ///< (f) ascending
  std::vector<std::uint16_t> group_ids;            ///< (g) ascending, distinct
  std::vector<std::int32_t> group_count;           ///< (g)
};

/// Number of CUDA devices (0 when there is no driver or no GPU).
int cuda_device_count_raw();

/// Runs extract_boundary (surface/extract_surface_impl.h) on the device for m tets given in host
/// memory: `tets` (m) node ids, `group` (m). narrow: use 64-bit keys (every id < 2^21).
/// Throws std::runtime_error on CUDA errors, thrust::system_error on allocation failure.
void extract_boundary_cuda(const std::array<std::int32_t, 4>* tets, const std::uint16_t* group,
                           std::int32_t m, bool narrow, HostBoundary& out);

}  // namespace serosa::surface::detail
