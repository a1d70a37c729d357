// Cutting benchmarks (docs/BENCHMARKS.md "Cutting"), on structured grids of n^3 cubes of edge kH,
// 6 Kuhn tets each, generated here:
//   BM_CutVsSize/n        one pattern cut by the same small oblique blade on meshes of about 10k
//                         (n = 12), 100k (n = 26) and 1M (n = 55) tets. The blade sits at the
//                         same place in cell units, so it touches the same tets on every size.
//   BM_CutVsBlade/s       the same on the 100k mesh with blades of half-size s cells: time
//                         against tets touched.
//   BM_Method/m/b         pattern (0), remove (1) and snap (2) on the 48k mesh (n = 20), blade b:
//                         0 a covering oblique cut through the whole block, 1 a partial one that
//                         ends inside it. Counters: tets touched and created, nodes added, volume
//                         lost, minimum quality after, and the distance from the blade polygon of
//                         the new boundary faces off the old surface (the cut surface), in cell
//                         edges (max and area-weighted mean), and their area (both sides of the
//                         crack; the pattern method's is exactly twice the blade's section of the
//                         mesh). Measured by cutting/cut_accuracy.h, as `serosa bench cutting`.
//   BM_SecondPass/s/p     pattern cuts by blades of half-size s/10 cells inside the 48k mesh,
//                         CutOptions::reopen_pinned off (p = 0) or on (1): time, crack area over
//                         twice the blade's, tets created and still pinned, minimum quality.
//   BM_Stroke/k/m         a scissors blade 12 cells long closing over a corner of the 48k mesh
//                         in k thin steps in an oblique plane, cut step by step with cut_mesh
//                         (m = 0) or as one ProgressiveCut stroke (m = 1): time of the whole
//                         stroke, tets created, crack area over that of one cut_mesh by the
//                         whole sector, minimum quality. Step by step, a run whose mesh
//                         passes 1M tets stops with an error (it about doubles per step).
// Time per cut = candidate query through the TetBvh + the cut + apply(mesh, delta) +
// TetBvh::update. The mesh and its BVH are built once per size; after each timed cut they are
// reset outside the timing (manual timing of exactly those four steps) by copy assignment from the
// pristine ones (which keeps the working arrays' capacity, so the timed apply() and update() do not
// reallocate), so every iteration cuts the same mesh with the same BVH. Counters cut_us, apply_us
// and update_us split the time; first_cut_us is one cut on a fresh copy given spare capacity
// as the app does after loading (reserve_for_cuts, a freshly built TetBvh); bvh_depth is the BVH's
// depth before the cut.
//
//   serosa_bench_cutting --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_accuracy.h"
#include "cutting/cut_method.h"
#include "cutting/progressive_cut.h"
#include "cutting/reserve.h"
#include "cutting/snap_cut.h"
#include "cutting/tet_bvh.h"
#include "engine/kuhn_grid.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {
namespace {

constexpr double kH = 0.002;  // cell edge, m (2 mm)

/// n x n x n cubes of edge kH, 6 Kuhn tets each (6 n^3 tets), one group.
TetMesh grid(int n) { return kuhn_grid(n, kH); }

/// An oblique square blade of half-size `half` cells centred at `centre` (cells).
ConvexPolygon blade(const Vec3& centre, double half) {
  const Vec3 n = Vec3(1.0, 0.31, 0.17).normalized();
  Vec3 u = n.cross(Vec3(0.13, 1.0, 0.29)).normalized();
  const Vec3 v = n.cross(u);
  const Vec3 c = centre * kH;
  const double s = half * kH;
  return ConvexPolygon(
      {c - s * u - s * v, c + s * u - s * v, c + s * u + s * v, c - s * u + s * v});
}

/// The small blade of BM_CutVsSize: inside the n = 12 grid, so the same tets on every size.
ConvexPolygon small_blade(double half = 2.0) { return blade(Vec3(6.1, 6.05, 5.95), half); }

struct Fixture {
  TetMesh pristine;  ///< the grid as built
  std::unique_ptr<TetBvh> pristine_bvh;
  TetMesh mesh;  ///< the copy each iteration cuts (reset by assignment: capacity is kept)
  std::unique_ptr<TetBvh> bvh;
  std::int32_t depth = 0;
};

/// Mesh and BVH of grid n, built once per process.
Fixture& fixture(int n) {
  static std::map<int, std::unique_ptr<Fixture>> cache;
  auto& f = cache[n];
  if (!f) {
    f = std::make_unique<Fixture>();
    f->pristine = grid(n);
    f->pristine_bvh = std::make_unique<TetBvh>(f->pristine);
    f->depth = f->pristine_bvh->depth();
    f->mesh = f->pristine;
    f->bvh = std::make_unique<TetBvh>(*f->pristine_bvh);
  }
  return *f;
}

/// Back to the pristine mesh and BVH (copy assignment: no reallocation once grown).
void reset(Fixture& f) {
  f.mesh = f.pristine;
  *f.bvh = *f.pristine_bvh;
}

using Clock = std::chrono::steady_clock;
double us(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::micro>(b - a).count();
}

/// One timed cut per iteration of the pristine mesh, reset outside the timing; fills the split
/// counters. first_cut_us: the first cut on a fresh copy of the mesh given spare capacity by
/// reserve_for_cuts and a BVH built from it, as the app has right after loading (no per-tet
/// array reallocates in that cut), not in the average.
CutResult run_cuts(benchmark::State& state, Fixture& f, const ConvexPolygon& b, CutMethod method,
                   const CutOptions& options = {}) {
  {
    // As the app after loading: spare capacity in the mesh (CuttingStage::step) and a BVH built
    // from it (with its own spare; a copied TetBvh would have none).
    TetMesh mesh = f.pristine;
    reserve_for_cuts(mesh);
    TetBvh bvh(mesh);
    const auto t0 = Clock::now();
    CutResult r = cut_with(method, mesh, b, options, bvh.as_query());
    const auto t1 = Clock::now();
    apply(mesh, r.delta);
    const auto t2 = Clock::now();
    bvh.update(mesh, r.delta);
    const auto t3 = Clock::now();
    state.counters["first_cut_us"] = us(t0, t3);
    state.counters["first_apply_us"] = us(t1, t2);
    state.counters["first_update_us"] = us(t2, t3);
  }
  // Warm-up: grows the working copy's arrays once.
  reset(f);
  {
    CutResult r = cut_with(method, f.mesh, b, options, f.bvh->as_query());
    apply(f.mesh, r.delta);
    f.bvh->update(f.mesh, r.delta);
  }
  reset(f);
  double cut_us = 0.0, apply_us = 0.0, update_us = 0.0;
  CutResult last;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    CutResult r = cut_with(method, f.mesh, b, options, f.bvh->as_query());
    const auto t1 = Clock::now();
    apply(f.mesh, r.delta);
    const auto t2 = Clock::now();
    f.bvh->update(f.mesh, r.delta);
    const auto t3 = Clock::now();
    state.SetIterationTime(std::chrono::duration<double>(t3 - t0).count());
    cut_us += us(t0, t1);
    apply_us += us(t1, t2);
    update_us += us(t2, t3);
    last = std::move(r);
    reset(f);  // not timed (manual time)
  }
  const auto avg = benchmark::Counter::kAvgIterations;
  state.counters["cut_us"] = benchmark::Counter(cut_us, avg);
  state.counters["apply_us"] = benchmark::Counter(apply_us, avg);
  state.counters["update_us"] = benchmark::Counter(update_us, avg);
  state.counters["tets"] = static_cast<double>(f.mesh.num_tets());
  state.counters["tets_touched"] = static_cast<double>(last.stats.tets_removed);
  state.counters["bvh_depth"] = f.depth;
  return last;
}

void BM_CutVsSize(benchmark::State& state) {
  Fixture& f = fixture(static_cast<int>(state.range(0)));
  run_cuts(state, f, small_blade(), CutMethod::kPattern);
}
BENCHMARK(BM_CutVsSize)
    ->Arg(12)
    ->Arg(26)
    ->Arg(55)
    ->Iterations(15)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

void BM_CutVsBlade(benchmark::State& state) {
  Fixture& f = fixture(26);
  const ConvexPolygon b = blade(Vec3(13.1, 13.05, 12.95), static_cast<double>(state.range(0)));
  run_cuts(state, f, b, CutMethod::kPattern);
}
BENCHMARK(BM_CutVsBlade)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(8)
    ->Arg(16)
    ->Iterations(15)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

void BM_Method(benchmark::State& state) {
  const auto method = static_cast<CutMethod>(state.range(0));
  Fixture& f = fixture(20);
  const ConvexPolygon b = state.range(1) == 0 ? blade(Vec3(10.1, 10.05, 9.95), 40.0)
                                              : blade(Vec3(3.1, 10.05, 9.95), 8.0);
  state.SetLabel(std::string(to_string(method)) + (state.range(1) == 0 ? " covering" : " partial"));
  // Accuracy of one cut, untimed, on a copy.
  {
    TetMesh after = f.pristine;
    CutResult r = cut_with(method, after, b, {}, f.pristine_bvh->as_query());
    apply(after, r.delta);
    const CutAccuracy a = measure_cut(f.pristine, after, b, kH);
    state.counters["volume_lost_rel"] = a.volume_lost_rel;
    state.counters["min_quality"] = a.min_quality;
    state.counters["max_dist_cells"] = a.max_dist_m / kH;
    state.counters["mean_dist_cells"] = a.mean_dist_m / kH;
    state.counters["cut_area_cm2"] = a.cut_area_m2 * 1e4;
    state.counters["tets_created"] = static_cast<double>(r.stats.tets_added - r.stats.tets_removed);
    state.counters["nodes_added"] = static_cast<double>(r.stats.nodes_added);
    if (method == CutMethod::kPattern) {  // partial tets split welded: the crack stops short there
      state.counters["tets_partial"] = static_cast<double>(r.stats.tets_partial);
      state.counters["tets_pinned"] = static_cast<double>(r.stats.tets_pinned);
      state.counters["tets_short"] = static_cast<double>(r.stats.tets_short);
    }
    if (method == CutMethod::kSnap) {  // crossing edges snapping could not resolve
      SnapStats st;
      (void)snap_cut(f.pristine, b, {}, f.pristine_bvh->as_query(), &st);
      state.counters["snap_crossing_edges"] = static_cast<double>(st.crossing_edges);
      state.counters["snap_unresolved"] = static_cast<double>(st.edges_unresolved);
    }
  }
  run_cuts(state, f, b, method);
}
// The second pass (CutOptions::reopen_pinned) on blades about a tet wide, inside the 48k mesh:
// half-size range(0) / 10 cells, second pass off (0) or on (1). Counters: what the cut opened
// (crack area over twice the blade's area), tets created, tets still pinned, tets whose crack
// misses part of the blade's share of their section (an upper bound with the second pass),
// minimum quality.
void BM_SecondPass(benchmark::State& state) {
  Fixture& f = fixture(20);
  const ConvexPolygon b =
      blade(Vec3(10.3, 10.15, 9.85), static_cast<double>(state.range(0)) / 10.0);
  CutOptions o;
  o.reopen_pinned = state.range(1) != 0;
  state.SetLabel(o.reopen_pinned ? "second pass" : "one pass");
  {
    TetMesh after = f.pristine;
    CutResult r = cut_mesh(after, b, o, f.pristine_bvh->as_query());
    apply(after, r.delta);
    const CutAccuracy a = measure_cut(f.pristine, after, b, kH);
    state.counters["opened"] = a.cut_area_m2 / (2.0 * b.area());
    state.counters["min_quality"] = a.min_quality;
    state.counters["tets_created"] = static_cast<double>(r.stats.tets_added - r.stats.tets_removed);
    state.counters["tets_pinned"] = static_cast<double>(r.stats.tets_pinned);
    state.counters["tets_short"] = static_cast<double>(r.stats.tets_short);
  }
  run_cuts(state, f, b, CutMethod::kPattern, o);
}
BENCHMARK(BM_SecondPass)
    ->ArgsProduct({{5, 10, 20, 40}, {0, 1}})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

// A stroke of range(0) thin steps (a scissors blade of 12 cells closing by 80 degrees in an
// oblique plane through a corner of the 48k mesh), step by step with cut_mesh (range(1) = 0) or as
// one ProgressiveCut (1). Each iteration cuts the pristine mesh (reset untimed); the time is the
// whole stroke (query, cut, apply, BVH update per step). Counters from the last iteration.
void BM_Stroke(benchmark::State& state) {
  Fixture& f = fixture(20);
  const int steps = static_cast<int>(state.range(0));
  const bool progressive = state.range(1) != 0;
  state.SetLabel(progressive ? "progressive" : "step by step");
  const Vec3 n = Vec3(1.0, 0.31, 0.17).normalized();
  const Vec3 a = n.cross(Vec3(0.13, 1.0, 0.29)).normalized(), b = n.cross(a);
  const Vec3 hinge = Vec3(3.1, 2.05, 1.95) * kH;
  const double length = 12.0 * kH, a0 = 0.0, a1 = 80.0 * 3.141592653589793 / 180.0;
  auto tip = [&](double t) -> Vec3 { return hinge + length * (std::cos(t) * a + std::sin(t) * b); };
  std::vector<ConvexPolygon> polys;
  std::vector<Vec3> sector{hinge};
  for (int k = 0; k <= steps; ++k) sector.push_back(tip(a0 + (a1 - a0) * k / steps));
  for (int k = 0; k < steps; ++k)
    polys.push_back(ConvexPolygon({hinge, sector[k + 1], sector[k + 2]}));
  const ConvexPolygon whole(sector);
  // One stroke; false when the mesh grew past 1M tets (step by step, thin steps re-split the
  // pieces ahead of the crack front and the mesh about doubles per step).
  auto stroke_once = [&]() {
    ProgressiveCut stroke;
    for (const ConvexPolygon& p : polys) {
      CutResult r = progressive ? stroke.cut(f.mesh, p, f.bvh->as_query())
                                : cut_mesh(f.mesh, p, {}, f.bvh->as_query());
      apply(f.mesh, r.delta);
      if (progressive) stroke.applied(f.mesh, r.delta);
      f.bvh->update(f.mesh, r.delta);
      if (f.mesh.num_tets() > 1000000) return false;
    }
    return true;
  };
  reset(f);
  if (!stroke_once()) {  // warm-up (grows the working arrays once), and the growth guard
    state.SkipWithError("grew past 1M tets");
    reset(f);
    return;
  }
  std::int64_t tets_after = 0;
  for (auto _ : state) {
    reset(f);
    const auto t0 = Clock::now();
    stroke_once();
    state.SetIterationTime(std::chrono::duration<double>(Clock::now() - t0).count());
    tets_after = f.mesh.num_tets();
  }
  const CutAccuracy acc = measure_cut(f.pristine, f.mesh, whole, kH);
  TetMesh once = f.pristine;
  CutResult r1 = cut_mesh(once, whole, {}, f.pristine_bvh->as_query());
  apply(once, r1.delta);
  const CutAccuracy one = measure_cut(f.pristine, once, whole, kH);
  state.counters["tets_created"] = static_cast<double>(tets_after - f.pristine.num_tets());
  state.counters["opened_vs_one_cut"] = acc.cut_area_m2 / one.cut_area_m2;
  state.counters["min_quality"] = acc.min_quality;
  reset(f);
}
BENCHMARK(BM_Stroke)
    ->ArgsProduct({{1, 2, 4, 8, 16, 64}, {0, 1}})
    ->Iterations(5)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

BENCHMARK(BM_Method)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace serosa::cutting

BENCHMARK_MAIN();
