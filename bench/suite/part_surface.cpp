// `serosa bench surface`: boundary extraction, time only. On generated blocks of Kuhn tets (two
// groups) a sequence of scissor cuts is applied; after each cut the surface is rebuilt by
//   - full extraction on the CPU, Thrust serial backend (1 thread) and OpenMP (2 threads),
//   - full extraction on the GPU (Thrust CUDA), only when built with CUDA and a device is present,
//   - the incremental update from the cut's TopologyDelta (surface/update_surface.h),
// all with face_cut decided against the original surface. The results must be the same surface:
// CPU 1 and 2 threads and CUDA face for face in the same order, the incremental one as the same
// set of (oriented faces, tet, group, cut flag) per group. The part throws otherwise.
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "bench/suite/bench_parts.h"
#include "cutting/cut_mesh.h"
#include "engine/kuhn_grid.h"
#include "engine/topology_delta.h"
#include "surface/extract_surface.h"
#include "surface/update_surface.h"

namespace serosa::bench {
namespace {

using Clock = std::chrono::steady_clock;
using surface::SurfaceMesh;

constexpr double kH = 0.002;  // cell edge, m

/// Scissor cut number `i` of a sequence on the block of n cells: 12 x 8 mm from the top down,
/// across the middle, each one 1.3 cells further along x, slightly tilted (no node on a blade).
cutting::ConvexPolygon scissor(int n, int i) {
  const double top = n * kH;
  const Vec3 c((0.3 + 0.1 * i) * top + 0.37 * kH, 0.5 * top, top);
  const double t = 0.1 * kH;
  return cutting::ConvexPolygon({c + Vec3(t, -6 * kH, kH), c + Vec3(t, 6 * kH, kH),
                                 c + Vec3(-t, 6 * kH, -4 * kH), c + Vec3(-t, -6 * kH, -4 * kH)});
}

bool identical(const SurfaceMesh& a, const SurfaceMesh& b) {
  if (a.groups.size() != b.groups.size()) return false;
  for (std::size_t g = 0; g < a.groups.size(); ++g)
    if (a.groups[g].group != b.groups[g].group || a.groups[g].offset != b.groups[g].offset ||
        a.groups[g].count != b.groups[g].count)
      return false;
  return a.faces == b.faces && a.face_tet == b.face_tet && a.face_group == b.face_group &&
         a.face_cut == b.face_cut;
}

/// The surface as a sorted list of (group, face rotated to its smallest node first, tet, cut).
using FaceRecord = std::tuple<std::uint16_t, std::array<std::int32_t, 3>, std::int32_t, int>;
std::vector<FaceRecord> canonical(const SurfaceMesh& s) {
  std::vector<FaceRecord> out;
  out.reserve(s.faces.size());
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    std::array<std::int32_t, 3> t{s.faces[f][0], s.faces[f][1], s.faces[f][2]};
    const auto first = std::min_element(t.begin(), t.end());
    std::rotate(t.begin(), first, t.end());
    out.emplace_back(s.face_group[f], t, s.face_tet[f], s.face_cut[f]);
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Group ranges tile the faces, ascending, and every face is in its range's group.
bool well_grouped(const SurfaceMesh& s) {
  std::int32_t next = 0;
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    const auto& r = s.groups[g];
    if (r.offset != next || r.count <= 0 || (g > 0 && s.groups[g - 1].group >= r.group))
      return false;
    for (std::int32_t f = r.offset; f < r.offset + r.count; ++f)
      if (s.face_group[static_cast<std::size_t>(f)] != r.group) return false;
    next = r.offset + r.count;
  }
  return next == s.num_faces();
}

[[noreturn]] void mismatch(const char* what, int n, int cut) {
  std::string msg = "surface: ";
  msg.append(what).append(" (block of ").append(std::to_string(n)).append("^3 cells, after cut ");
  msg.append(std::to_string(cut + 1)).append(")");
  throw std::runtime_error(msg);
}

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

}  // namespace

PartResult run_surface_part(const BenchOptions& options) {
  const std::vector<int> sizes =
      options.quick ? std::vector<int>{8, 16} : std::vector<int>{10, 20, 40};
  const int cuts = options.quick ? 3 : 5;
  const bool cuda = surface::cuda_available();
  const std::vector<std::string> columns = {"tets", "faces", "ms_per_update"};
  Table serial{"surface_full_cpu_1thread", columns, {}, {}};
  Table omp2{"surface_full_cpu_2threads", columns, {}, {}};
  Table gpu{"surface_full_cuda", columns, {}, {}};
  Table incremental{"surface_incremental", columns, {}, {}};
  const int threads_before = omp_get_max_threads();
  for (const int n : sizes) {
    TetMesh mesh = kuhn_grid(n, kH, true);
    SurfaceMesh s = surface::extract_surface(mesh);
    const surface::OriginalSurface original(mesh, s);
    surface::FaceTable table = surface::build_face_table(mesh, s);
    // Fastest of the cuts (the machine may be shared: the minimum is the least disturbed).
    double t_serial = 1e300, t_omp = 1e300, t_gpu = 1e300, t_inc = 1e300;
    for (int c = 0; c < cuts; ++c) {
      cutting::CutResult cut = cutting::cut_mesh(mesh, scissor(n, c));
      apply(mesh, cut.delta);
      auto t0 = Clock::now();
      surface::update_surface(s, table, mesh, cut.delta, &original);
      t_inc = std::min(t_inc, ms_since(t0));
      omp_set_num_threads(1);
      t0 = Clock::now();
      const SurfaceMesh full1 = surface::extract_surface(mesh, original);
      t_serial = std::min(t_serial, ms_since(t0));
      omp_set_num_threads(2);
      t0 = Clock::now();
      const SurfaceMesh full2 = surface::extract_surface(mesh, original);
      t_omp = std::min(t_omp, ms_since(t0));
      omp_set_num_threads(threads_before);
      if (!identical(full1, full2))
        mismatch("1 and 2 CPU threads extracted different surfaces", n, c);
      if (!well_grouped(s) || canonical(s) != canonical(full1))
        mismatch("the incremental update differs from the full extraction", n, c);
      if (cuda) {
        t0 = Clock::now();
        const SurfaceMesh g = surface::extract_surface(mesh, original, surface::Backend::kCuda);
        t_gpu = std::min(t_gpu, ms_since(t0));
        if (!identical(g, full1)) mismatch("CUDA and CPU extracted different surfaces", n, c);
      }
    }
    const double tets = mesh.num_tets(), faces = s.num_faces();
    const std::string label = std::to_string(n) + "^3 cells";
    serial.add(label, {tets, faces, t_serial});
    omp2.add(label, {tets, faces, t_omp});
    incremental.add(label, {tets, faces, t_inc});
    if (cuda) gpu.add(label, {tets, faces, t_gpu});
  }
  PartResult result;
  Plot p{"surface_time",
         "Surface after a cut: full extraction against incremental update",
         "tets",
         "ms per surface update (fastest of the cuts)",
         true,
         true,
         {}};
  p.series.push_back({serial.name, "tets", "ms_per_update", "full, CPU 1 thread", false, false});
  p.series.push_back(
      {omp2.name, "tets", "ms_per_update", "full, CPU 2 threads (OpenMP)", false, false});
  if (cuda)
    p.series.push_back({gpu.name, "tets", "ms_per_update", "full, GPU (CUDA)", false, false});
  p.series.push_back({incremental.name, "tets", "ms_per_update", "incremental", false, false});
  result.plots.push_back(std::move(p));
  result.tables.push_back(std::move(serial));
  result.tables.push_back(std::move(omp2));
  if (cuda) result.tables.push_back(std::move(gpu));
  result.tables.push_back(std::move(incremental));
  std::string note = "surface: ";
  note.append(std::to_string(cuts)).append(" cuts per size; every method gave the same surface");
  note.append(cuda ? "; CUDA measured"
                   : "; no CUDA device in this build/run: the GPU row is absent");
  result.notes.push_back(std::move(note));
  return result;
}

}  // namespace serosa::bench
