// extract_surface_cuda and cuda_device_count: wrap the CUDA library
// (surface/extract_boundary_cuda.h) when it is built (SEROSA_HAVE_CUDA), else the "no CUDA"
// fallbacks (surface/extract_surface.h).
#include <stdexcept>
#include <utility>

#include "surface/extract_surface.h"
#include "surface/extract_surface_impl.h"
#include "surface/group_ranges.h"

#if defined(SEROSA_HAVE_CUDA)
#include "surface/extract_boundary_cuda.h"
#endif

namespace serosa::surface {

#if defined(SEROSA_HAVE_CUDA)

int cuda_device_count() { return detail::cuda_device_count_raw(); }

SurfaceMesh extract_surface_cuda(const TetMesh& mesh, KeyWidth keys) {
  if (mesh.group.size() != mesh.tets.size())
    throw std::invalid_argument("extract_surface: group and tets differ in size");
  const bool narrow = detail::pick_narrow_keys(mesh.tets, keys == KeyWidth::kWide);
  if (cuda_device_count() <= 0)
    throw std::runtime_error("extract_surface_cuda: no CUDA device present");
  detail::HostBoundary b;
  detail::extract_boundary_cuda(mesh.tets.data(), mesh.group.data(), mesh.num_tets(), narrow, b);
  SurfaceMesh s;
  s.faces = std::move(b.faces);
  s.face_tet = std::move(b.face_tet);
  s.face_group = std::move(b.face_group);
  s.face_cut.assign(s.faces.size(), 0);
  set_group_ranges(s, b.group_ids.data(), b.group_count.data(), b.group_ids.size());
  s.topology_version = mesh.topology_version;
  return s;
}

#else

int cuda_device_count() { return 0; }

SurfaceMesh extract_surface_cuda(const TetMesh& /*mesh*/, KeyWidth /*keys*/) {
  throw std::runtime_error("extract_surface_cuda: Serosa was built without CUDA (nvcc not found)");
}

#endif

}  // namespace serosa::surface
