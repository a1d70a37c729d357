// Full boundary extraction of a tet mesh (paper Figure 10) on Thrust's OpenMP or CUDA backend.
//
// How the CUDA backend links: when nvcc is found, surface/extract_surface_cuda.cu (Eigen-free raw
// arrays, surface/extract_boundary_cuda.h) is built into serosa_surface_cuda, which serosa_surface
// links PUBLIC (surface/CMakeLists.txt). So SEROSA_HAVE_CUDA is defined alike for serosa_surface
// and every target using it, and extract_surface(mesh, Backend::kCuda) works from anywhere, with
// no weak symbols or registry. surface/extract_surface_cuda_entry.cpp defines the two CUDA entry
// points below either way: wrapping the device code, or as "no CUDA" fallbacks
// (cuda_device_count() == 0, extract_surface_cuda throws) when CUDA is not built.
#pragma once

#include <cstdint>

#include "engine/tet_mesh.h"
#include "surface/cut_faces.h"
#include "surface/surface_mesh.h"

namespace serosa::surface {

enum class Backend {
  kCpu,   ///< Thrust OpenMP backend (threads: OMP_NUM_THREADS / omp_set_num_threads)
  kCuda,  ///< Thrust CUDA backend; needs cuda_available()
};

/// Face key packing (surface/face_key.h). kAuto picks the 64-bit key when num_nodes <= 2^21,
/// else the 96-bit one; kWide forces the 96-bit key (tests use it to cover that path).
enum class KeyWidth { kAuto, kWide };

/// The boundary surface of `mesh`: faces used by exactly one tet, oriented outward from that tet
/// (tets are positively oriented in rest space), grouped by the tets' group (one contiguous range
/// per group, ascending group id; inside a group, faces are in ascending sorted-node-id order).
/// Faces shared by three or more tets (an invalid mesh) are not boundary faces.
/// Throws std::invalid_argument for more than 2^30 tets or a negative node id, std::runtime_error
/// for Backend::kCuda without a usable device.
/// Every face has face_cut = 0 (no reference: the current surface counts as original).
[[nodiscard]] SurfaceMesh extract_surface(const TetMesh& mesh, Backend backend = Backend::kCpu);

/// The same, with face_cut decided against `original` (the organ's boundary before any cut;
/// rule in surface/cut_faces.h), on the CPU after the backend's extraction, O(f).
[[nodiscard]] SurfaceMesh extract_surface(const TetMesh& mesh, const OriginalSurface& original,
                                          Backend backend = Backend::kCpu);

/// Options of the CPU extraction.
struct CpuOptions {
  KeyWidth keys = KeyWidth::kAuto;
  /// Meshes with fewer tets run on Thrust's serial backend (thrust::cpp): starting OpenMP threads
  /// costs more than it saves on small meshes, badly so on a busy machine. 0: OpenMP whenever
  /// more than one OpenMP thread is allowed. With one thread the serial backend is used anyway:
  /// it was faster (66 against 115 ms for 101,400 tets on the 2-core dev VM).
  std::int32_t serial_below_tets = 16384;
};

/// The CPU extraction (Thrust OpenMP backend; serial for small meshes or one thread).
[[nodiscard]] SurfaceMesh extract_surface_cpu(const TetMesh& mesh, const CpuOptions& options = {});

/// The CUDA extraction: the same faces in the same order as extract_surface_cpu. Throws
/// std::runtime_error when CUDA was not built or no device is present.
[[nodiscard]] SurfaceMesh extract_surface_cuda(const TetMesh& mesh,
                                               KeyWidth keys = KeyWidth::kAuto);

/// Number of CUDA devices usable by this process (0 when CUDA was not built, no driver or no GPU).
[[nodiscard]] int cuda_device_count();

/// True when Backend::kCuda can run: built with CUDA and a device is present.
[[nodiscard]] inline bool cuda_available() { return cuda_device_count() > 0; }

}  // namespace serosa::surface
