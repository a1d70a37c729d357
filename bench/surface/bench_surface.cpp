// Surface benchmarks (docs/BENCHMARKS.md "Surface extraction and collision"): full Thrust
// extraction on the CPU with 1 and 2 OpenMP threads, the incremental update after one scissor
// cut, and the collision BVH (build, refit, local update, queries), on structured grids of about
// 10k, 100k and 1M tets generated here. Arguments: cells per side n (6 n^3 tets) and threads.
//
//   serosa_bench_surface --benchmark_min_time=0.2 --benchmark_repetitions=3
//
// glibc returns the extraction's large scratch arrays to the kernel after each call until its
// dynamic mmap threshold has grown, so a benchmark's result depends on what ran before it. The
// docs give both: each benchmark alone with default malloc ("cold", page faults included) and the
// whole run with the pages kept ("warm"):
//   GLIBC_TUNABLES=glibc.malloc.trim_threshold=1073741824:glibc.malloc.mmap_threshold=33554432
#include <benchmark/benchmark.h>
#include <omp.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/geometry/surface_bvh.h"
#include "engine/kuhn_grid.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "surface/cut_faces.h"
#include "surface/extract_surface.h"
#include "surface/surface_normals.h"
#include "surface/update_surface.h"

namespace serosa::surface {
namespace {
using geometry::RayHit;
using geometry::SurfaceBvh;

constexpr double kH = 0.002;  // cell edge, m (2 mm)

/// n x n x n cubes of edge kH, 6 Kuhn tets each (6 n^3 tets), two groups (x halves).
TetMesh grid(int n) { return kuhn_grid(n, kH, true); }

/// One scissor cut of fixed size (12 x 8 mm, whatever the mesh's size) from the top side down,
/// across the middle of the grid: a complete cut of the tets it crosses.
cutting::CutResult one_cut(const TetMesh& m, int n) {
  const double top = n * kH;
  const Vec3 c(0.5 * top + 0.37 * kH, 0.5 * top, top);
  const double t = 0.1 * kH;  // slight tilt: no node on the blade
  const cutting::ConvexPolygon blade({c + Vec3(t, -6 * kH, kH), c + Vec3(t, 6 * kH, kH),
                                      c + Vec3(-t, 6 * kH, -4 * kH),
                                      c + Vec3(-t, -6 * kH, -4 * kH)});
  return cutting::cut_mesh(m, blade);
}

void set_counters(benchmark::State& st, const TetMesh& m, const SurfaceMesh& s) {
  st.counters["tets"] = static_cast<double>(m.num_tets());
  st.counters["faces"] = static_cast<double>(s.num_faces());
}

// Full extraction (Thrust, paper Figure 10) on the CPU; 1 thread runs Thrust's serial backend
// (CpuOptions), 2 threads its OpenMP one.
void BM_FullExtraction(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const int threads = static_cast<int>(st.range(1));
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  const TetMesh m = grid(n);
  SurfaceMesh s = extract_surface(m);  // untimed warm-up: the allocator keeps these pages
  for (auto _ : st) {
    s = extract_surface(m);
    benchmark::DoNotOptimize(s.faces.data());
  }
  set_counters(st, m, s);
  omp_set_num_threads(before);
}

// Full extraction plus face_cut against the original surface (what a rebuild after a cut costs).
void BM_FullExtractionWithCutFlags(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const int threads = static_cast<int>(st.range(1));
  const int before = omp_get_max_threads();
  omp_set_num_threads(threads);
  TetMesh m = grid(n);
  const OriginalSurface original(m, extract_surface(m));
  cutting::CutResult cut = one_cut(m, n);
  apply(m, cut.delta);
  SurfaceMesh s = extract_surface(m, original);  // untimed warm-up
  for (auto _ : st) {
    s = extract_surface(m, original);
    benchmark::DoNotOptimize(s.faces.data());
  }
  set_counters(st, m, s);
  omp_set_num_threads(before);
}

// Incremental update after one cut (with face_cut against the original surface). The surface and
// face table are restored outside the timed region before every iteration.
void BM_IncrementalAfterOneCut(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const bool flags = st.range(1) != 0;  // face_cut against the original surface
  TetMesh m = grid(n);
  const SurfaceMesh s0 = extract_surface(m);
  const OriginalSurface original(m, s0);
  const FaceTable table0 = build_face_table(m, s0);
  cutting::CutResult cut = one_cut(m, n);
  apply(m, cut.delta);
  std::vector<std::int32_t> changed;
  SurfaceMesh s = s0;
  FaceTable table = table0;
  const OriginalSurface* ref = flags ? &original : nullptr;
  update_surface(s, table, m, cut.delta, ref, &changed);  // untimed warm-up
  for (auto _ : st) {
    st.PauseTiming();
    s = s0;
    table = table0;
    st.ResumeTiming();
    update_surface(s, table, m, cut.delta, ref, &changed);
    benchmark::DoNotOptimize(s.faces.data());
  }
  set_counters(st, m, s);
  st.counters["tets_removed"] = static_cast<double>(cut.delta.removed_tets.size());
  st.counters["tets_added"] = static_cast<double>(cut.delta.added_tets.size());
  st.counters["slots_changed"] = static_cast<double>(changed.size());
}

/// A deformed copy of the positions (so that refits have work to do).
std::vector<Vec3> wobble(const TetMesh& m, double amp, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amp, amp);
  std::vector<Vec3> x = m.x;
  for (Vec3& p : x) p += Vec3(u(rng), u(rng), u(rng));
  return x;
}

void BM_BvhBuild(benchmark::State& st) {
  const TetMesh m = grid(static_cast<int>(st.range(0)));
  const SurfaceMesh s = extract_surface(m);
  SurfaceBvh bvh;
  for (auto _ : st) bvh.build(s, m.x);
  set_counters(st, m, s);
}

void BM_BvhRefit(benchmark::State& st) {
  const TetMesh m = grid(static_cast<int>(st.range(0)));
  const SurfaceMesh s = extract_surface(m);
  const std::vector<Vec3> x1 = wobble(m, 0.2 * kH, 1), x2 = wobble(m, 0.2 * kH, 2);
  SurfaceBvh bvh;
  bvh.build(s, x1);
  bool flip = false;
  for (auto _ : st) {
    bvh.refit(flip ? x1 : x2);
    flip = !flip;
  }
  set_counters(st, m, s);
}

// Local BVH update after the cut (update_surface's changed slots), against a rebuild.
void BM_BvhLocalUpdateAfterOneCut(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  TetMesh m = grid(n);
  SurfaceMesh s = extract_surface(m);
  FaceTable table = build_face_table(m, s);
  SurfaceBvh bvh0;
  bvh0.build(s, m.x);
  cutting::CutResult cut = one_cut(m, n);
  apply(m, cut.delta);
  std::vector<std::int32_t> changed;
  update_surface(s, table, m, cut.delta, nullptr, &changed);
  SurfaceBvh bvh;
  for (auto _ : st) {
    st.PauseTiming();
    bvh = bvh0;
    st.ResumeTiming();
    bvh.update(s, changed, m.x);
  }
  set_counters(st, m, s);
  st.counters["slots_changed"] = static_cast<double>(changed.size());
}

// Queries: 1000 random ones per iteration; counters give the time per query.
enum class Query { kClosest, kRay, kSegment };

void bvh_queries(benchmark::State& st, Query kind) {
  const int n = static_cast<int>(st.range(0));
  const TetMesh m = grid(n);
  const SurfaceMesh s = extract_surface(m);
  const std::vector<Vec3> x = wobble(m, 0.2 * kH, 3);
  SurfaceBvh bvh;
  bvh.build(s, x);
  std::mt19937 rng(4);
  const double size = n * kH;
  std::uniform_real_distribution<double> u(-0.2 * size, 1.2 * size);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  std::vector<Vec3> p(1000), q(1000);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p[i] = Vec3(u(rng), u(rng), u(rng));
    // Tool-sized segments (1 cm) for the segment query; directions for rays.
    q[i] = p[i] + 0.01 * Vec3(d(rng), d(rng), d(rng)).normalized();
  }
  std::vector<RayHit> hits;
  for (auto _ : st)
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (kind == Query::kClosest) {
        benchmark::DoNotOptimize(bvh.closest_point(x, p[i]));
      } else if (kind == Query::kRay) {
        benchmark::DoNotOptimize(bvh.raycast(x, p[i], q[i] - p[i]));
      } else {
        bvh.segment_all(x, p[i], q[i], hits);
        benchmark::DoNotOptimize(hits.data());
      }
    }
  st.counters["query"] = benchmark::Counter(
      static_cast<double>(p.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  set_counters(st, m, s);
}

void BM_BvhClosestPoint(benchmark::State& st) { bvh_queries(st, Query::kClosest); }
void BM_BvhRaycast(benchmark::State& st) { bvh_queries(st, Query::kRay); }
void BM_BvhSegmentAll(benchmark::State& st) { bvh_queries(st, Query::kSegment); }

void BM_RenderVertices(benchmark::State& st) {
  const TetMesh m = grid(static_cast<int>(st.range(0)));
  const SurfaceMesh s = extract_surface(m);
  RenderVertices r;
  for (auto _ : st) compute_render_vertices(s, m.x, {}, r);
  set_counters(st, m, s);
}

// n = 12, 26, 55: 10,368, 105,456 and 998,250 tets.
BENCHMARK(BM_FullExtraction)
    ->ArgsProduct({{12, 26, 55}, {1, 2}})
    ->ArgNames({"n", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_FullExtractionWithCutFlags)
    ->ArgsProduct({{12, 26, 55}, {2}})
    ->ArgNames({"n", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// The state is restored (copied) outside the timed region before each iteration; a fixed
// iteration count keeps those 1M-tet copies from dominating the run.
BENCHMARK(BM_IncrementalAfterOneCut)
    ->ArgsProduct({{12, 26, 55}, {1, 0}})
    ->ArgNames({"n", "flags"})
    ->Iterations(30)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhBuild)->Arg(12)->Arg(26)->Arg(55)->ArgName("n")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhRefit)->Arg(12)->Arg(26)->Arg(55)->ArgName("n")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhLocalUpdateAfterOneCut)
    ->Arg(12)
    ->Arg(26)
    ->Arg(55)
    ->ArgName("n")
    ->Iterations(20)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhClosestPoint)->Arg(12)->Arg(55)->ArgName("n")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhRaycast)->Arg(12)->Arg(55)->ArgName("n")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BvhSegmentAll)->Arg(12)->Arg(55)->ArgName("n")->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderVertices)->Arg(12)->Arg(55)->ArgName("n")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace serosa::surface

BENCHMARK_MAIN();
