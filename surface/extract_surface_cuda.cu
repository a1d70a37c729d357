// The extraction on Thrust's CUDA backend (nvcc): the same pipeline as the OpenMP one
// (surface/extract_surface_impl.h) on device memory.
#include <cuda_runtime.h>
#include <thrust/device_vector.h>
#include <thrust/system/cuda/execution_policy.h>

#include <stdexcept>
#include <string>

#include "surface/extract_boundary_cuda.h"
#include "surface/extract_surface_impl.h"

namespace serosa::surface::detail {
namespace {

/// Device-side tet and triangle: plain arrays with device-callable indexing (std::array's is not).
struct Tet4 {
  std::int32_t v[4];
  SEROSA_HD std::int32_t operator[](int k) const { return v[k]; }
};
struct Tri3 {
  std::int32_t v[3];
};
static_assert(sizeof(Tet4) == sizeof(std::array<std::int32_t, 4>));
static_assert(sizeof(Tri3) == sizeof(std::array<std::int32_t, 3>));

template <class T>
using DevVec = thrust::device_vector<T>;

void check(cudaError_t e, const char* what) {
  if (e != cudaSuccess)
    throw std::runtime_error(std::string("extract_surface_cuda: ") + what + ": " +
                             cudaGetErrorString(e));
}

template <class Key>
void run(const std::array<std::int32_t, 4>* tets, const std::uint16_t* group, std::int32_t m,
         HostBoundary& out) {
  const auto n = static_cast<std::size_t>(m);
  DevVec<Tet4> d_tets(n);
  DevVec<std::uint16_t> d_group(group, group + n);
  check(cudaMemcpy(thrust::raw_pointer_cast(d_tets.data()), tets, n * sizeof(Tet4),
                   cudaMemcpyHostToDevice),
        "copy tets");
  Boundary<DevVec, Tri3> b;
  extract_boundary<Key>(thrust::cuda::par, thrust::raw_pointer_cast(d_tets.data()),
                        thrust::raw_pointer_cast(d_group.data()), m, b);

  out.faces.resize(b.faces.size());
  check(cudaMemcpy(out.faces.data(), thrust::raw_pointer_cast(b.faces.data()),
                   b.faces.size() * sizeof(Tri3), cudaMemcpyDeviceToHost),
        "copy faces");
  out.face_tet.resize(b.face_tet.size());
  thrust::copy(b.face_tet.begin(), b.face_tet.end(), out.face_tet.begin());
  out.face_group.resize(b.face_group.size());
  thrust::copy(b.face_group.begin(), b.face_group.end(), out.face_group.begin());
  out.group_ids.resize(b.group_ids.size());
  thrust::copy(b.group_ids.begin(), b.group_ids.end(), out.group_ids.begin());
  out.group_count.resize(b.group_count.size());
  thrust::copy(b.group_count.begin(), b.group_count.end(), out.group_count.begin());
}

}  // namespace

int cuda_device_count_raw() {
  int n = 0;
  if (cudaGetDeviceCount(&n) != cudaSuccess) {
    (void)cudaGetLastError();  // clear the "no driver / no device" error
    return 0;
  }
  return n;
}

void extract_boundary_cuda(const std::array<std::int32_t, 4>* tets, const std::uint16_t* group,
                           std::int32_t m, bool narrow, HostBoundary& out) {
  out = HostBoundary{};
  if (m <= 0) return;
  if (narrow)
    run<NarrowKey>(tets, group, m, out);
  else
    run<WideKey>(tets, group, m, out);
}

}  // namespace serosa::surface::detail
