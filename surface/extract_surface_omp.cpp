// extract_surface on Thrust's OpenMP backend (g++; serial backend for small meshes), and the
// backend switch.
#include <thrust/system/cpp/execution_policy.h>
#include <thrust/system/omp/execution_policy.h>

#include <stdexcept>
#include <utility>
#include <vector>

#include "surface/extract_surface.h"
#include "surface/extract_surface_impl.h"
#include "surface/group_ranges.h"

namespace serosa::surface {
namespace {

template <class T>
using HostVec = std::vector<T>;

template <class Key, class Policy>
SurfaceMesh run(const Policy& policy, const TetMesh& mesh) {
  detail::Boundary<HostVec, Tri> b;
  detail::extract_boundary<Key>(policy, mesh.tets.data(), mesh.group.data(), mesh.num_tets(), b);
  SurfaceMesh s;
  s.faces = std::move(b.faces);
  s.face_tet = std::move(b.face_tet);
  s.face_group = std::move(b.face_group);
  set_group_ranges(s, b.group_ids.data(), b.group_count.data(), b.group_ids.size());
  s.topology_version = mesh.topology_version;
  return s;
}

}  // namespace

SurfaceMesh extract_surface_cpu(const TetMesh& mesh, const CpuOptions& options) {
  if (mesh.group.size() != mesh.tets.size())
    throw std::invalid_argument("extract_surface: group and tets differ in size");
  const bool narrow = detail::pick_narrow_keys(mesh.tets, options.keys == KeyWidth::kWide);
  if (mesh.num_tets() < options.serial_below_tets)
    return narrow ? run<NarrowKey>(thrust::cpp::par, mesh) : run<WideKey>(thrust::cpp::par, mesh);
  return narrow ? run<NarrowKey>(thrust::omp::par, mesh) : run<WideKey>(thrust::omp::par, mesh);
}

SurfaceMesh extract_surface(const TetMesh& mesh, Backend backend) {
  return backend == Backend::kCuda ? extract_surface_cuda(mesh) : extract_surface_cpu(mesh);
}

}  // namespace serosa::surface
