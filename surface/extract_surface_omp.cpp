// extract_surface on Thrust's OpenMP backend (g++; serial backend for small meshes), and the
// backend switch.
#include <omp.h>
#include <thrust/system/cpp/execution_policy.h>
#include <thrust/system/omp/execution_policy.h>

#include <memory>
#include <new>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "surface/extract_surface.h"
#include "surface/extract_surface_impl.h"
#include "surface/group_ranges.h"

namespace serosa::surface {
namespace {

// Default-initialising allocator: the pipeline's scratch arrays (4 m entries each) are written
// before they are read, so value-initialising them (a memset per array) is wasted work.
template <class T>
struct NoInit : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = NoInit<U>;
  };
  NoInit() = default;
  template <class U>
  explicit NoInit(const NoInit<U>& /*other*/) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using HostVec = std::vector<T, NoInit<T>>;

template <class Key, class Policy>
SurfaceMesh run(const Policy& policy, const TetMesh& mesh) {
  detail::Boundary<HostVec, Tri> b;
  detail::extract_boundary<Key>(policy, mesh.tets.data(), mesh.group.data(), mesh.num_tets(), b);
  SurfaceMesh s;
  s.faces.assign(b.faces.begin(), b.faces.end());
  s.face_tet.assign(b.face_tet.begin(), b.face_tet.end());
  s.face_group.assign(b.face_group.begin(), b.face_group.end());
  s.face_cut.assign(s.faces.size(), 0);
  set_group_ranges(s, b.group_ids.data(), b.group_count.data(), b.group_ids.size());
  s.topology_version = mesh.topology_version;
  return s;
}

}  // namespace

SurfaceMesh extract_surface_cpu(const TetMesh& mesh, const CpuOptions& options) {
  if (mesh.group.size() != mesh.tets.size())
    throw std::invalid_argument("extract_surface: group and tets differ in size");
  const bool narrow = detail::pick_narrow_keys(mesh.tets, options.keys == KeyWidth::kWide);
  if (mesh.num_tets() < options.serial_below_tets || omp_get_max_threads() == 1)
    return narrow ? run<NarrowKey>(thrust::cpp::par, mesh) : run<WideKey>(thrust::cpp::par, mesh);
  return narrow ? run<NarrowKey>(thrust::omp::par, mesh) : run<WideKey>(thrust::omp::par, mesh);
}

SurfaceMesh extract_surface(const TetMesh& mesh, Backend backend) {
  return backend == Backend::kCuda ? extract_surface_cuda(mesh) : extract_surface_cpu(mesh);
}

SurfaceMesh extract_surface(const TetMesh& mesh, const OriginalSurface& original, Backend backend) {
  SurfaceMesh s = extract_surface(mesh, backend);
  mark_cut_faces(s, mesh, original);
  return s;
}

}  // namespace serosa::surface
