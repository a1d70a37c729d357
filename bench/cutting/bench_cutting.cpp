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
//                         edges, and their area (both sides of the crack; the pattern method's is
//                         exactly twice the blade's section of the mesh).
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
#include <set>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_method.h"
#include "cutting/reserve.h"
#include "cutting/snap_cut.h"
#include "cutting/tet_bvh.h"
#include "engine/boundary.h"
#include "engine/mesh_quality.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {
namespace {

constexpr double kH = 0.002;  // cell edge, m (2 mm)

/// n x n x n cubes of edge kH, 6 Kuhn tets each (6 n^3 tets), one group.
TetMesh grid(int n) {
  TetMesh m;
  const auto id = [n](int i, int j, int k) { return (i * (n + 1) + j) * (n + 1) + k; };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) m.add_node(Vec3(i * kH, j * kH, k * kH));
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  m.tets.reserve(static_cast<std::size_t>(6 * n * n * n));
  m.group.reserve(m.tets.capacity());
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        for (const auto& p : perms) {
          std::array<int, 3> c{i, j, k};
          Tet t{};
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[static_cast<std::size_t>(p[s])];
            t[static_cast<std::size_t>(s) + 1] = id(c[0], c[1], c[2]);
          }
          const int tet = m.add_tet(t, 1);
          if (m.rest_volume(tet) < 0.0) std::swap(m.tets.back()[2], m.tets.back()[3]);
        }
  return m;
}

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
CutResult run_cuts(benchmark::State& state, Fixture& f, const ConvexPolygon& b, CutMethod method) {
  {
    // As the app after loading: spare capacity in the mesh (CuttingStage::step) and a BVH built
    // from it (with its own spare; a copied TetBvh would have none).
    TetMesh mesh = f.pristine;
    reserve_for_cuts(mesh);
    TetBvh bvh(mesh);
    const auto t0 = Clock::now();
    CutResult r = cut_with(method, mesh, b, {}, bvh.as_query());
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
    CutResult r = cut_with(method, f.mesh, b, {}, f.bvh->as_query());
    apply(f.mesh, r.delta);
    f.bvh->update(f.mesh, r.delta);
  }
  reset(f);
  double cut_us = 0.0, apply_us = 0.0, update_us = 0.0;
  CutResult last;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    CutResult r = cut_with(method, f.mesh, b, {}, f.bvh->as_query());
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

// Distance (m) from p to the convex polygon b.
double polygon_distance(const ConvexPolygon& b, const Vec3& p) {
  if (b.contains_projection(p)) return std::abs(b.signed_distance(p));
  double best = std::numeric_limits<double>::infinity();
  const auto& q = b.points();
  for (std::size_t i = 0; i < q.size(); ++i) {
    const Vec3& s = q[i];
    const Vec3 e = q[(i + 1) % q.size()] - s;
    const double t = std::clamp(e.dot(p - s) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (s + t * e - p).norm());
  }
  return best;
}

// Distance (m) from p to triangle (a, b, c).
double triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const Vec3 q = p - n * (n.dot(p - a) / n.squaredNorm());
  if (n.dot((b - q).cross(c - q)) >= 0.0 && n.dot((c - q).cross(a - q)) >= 0.0 &&
      n.dot((a - q).cross(b - q)) >= 0.0)
    return (p - q).norm();
  auto seg = [&](const Vec3& s, const Vec3& e) {
    const Vec3 d = e - s;
    const double t = std::clamp(d.dot(p - s) / d.squaredNorm(), 0.0, 1.0);
    return (s + t * d - p).norm();
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

struct Accuracy {
  double volume_lost_rel = 0.0;  ///< (V_before - V_after) / V_before (rest)
  double min_quality = 0.0;      ///< smallest mean-ratio quality after (rest)
  double max_dist_cells = 0.0;   ///< new boundary faces off the old surface: max vertex
                                 ///< distance from the blade polygon, in cell edges
  double cut_area_m2 = 0.0;      ///< their area (both sides)
};

// What one cut does to the mesh's geometry (not timed).
Accuracy accuracy(const TetMesh& before, const TetMesh& after, const ConvexPolygon& b) {
  Accuracy a;
  double vb = 0.0, va = 0.0;
  for (std::int32_t i = 0; i < before.num_tets(); ++i) vb += before.rest_volume(i);
  for (std::int32_t i = 0; i < after.num_tets(); ++i) va += after.rest_volume(i);
  a.volume_lost_rel = (vb - va) / vb;
  const std::vector<double> q = tet_qualities(after);
  a.min_quality = *std::min_element(q.begin(), q.end());
  const FaceCensus fb = face_census(before), fa = face_census(after);
  auto key = [](Tri t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::set<Tri> old;
  for (const BoundaryFace& f : fb.boundary) old.insert(key(f.nodes));
  // Old boundary faces near the blade (the only ones a new face can lie on).
  const Vec3 lo = b.box_min() - Vec3::Constant(3.0 * kH),
             hi = b.box_max() + Vec3::Constant(3.0 * kH);
  std::vector<Tri> near;
  for (const BoundaryFace& f : fb.boundary) {
    const Vec3& p = before.x[f.nodes[0]];
    if ((p.array() >= lo.array()).all() && (p.array() <= hi.array()).all()) near.push_back(f.nodes);
  }
  for (const BoundaryFace& f : fa.boundary) {
    if (old.contains(key(f.nodes))) continue;
    const Vec3 &p0 = after.x[f.nodes[0]], &p1 = after.x[f.nodes[1]], &p2 = after.x[f.nodes[2]];
    const Vec3 c = (p0 + p1 + p2) / 3.0;
    bool on_old = false;
    for (const Tri& o : near)
      if (triangle_distance(c, before.x[o[0]], before.x[o[1]], before.x[o[2]]) <= 1e-9 * kH) {
        on_old = true;
        break;
      }
    if (on_old) continue;
    for (const Vec3* p : {&p0, &p1, &p2})
      a.max_dist_cells = std::max(a.max_dist_cells, polygon_distance(b, *p) / kH);
    a.cut_area_m2 += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return a;
}

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
    const Accuracy a = accuracy(f.pristine, after, b);
    state.counters["volume_lost_rel"] = a.volume_lost_rel;
    state.counters["min_quality"] = a.min_quality;
    state.counters["max_dist_cells"] = a.max_dist_cells;
    state.counters["cut_area_cm2"] = a.cut_area_m2 * 1e4;
    state.counters["tets_created"] = static_cast<double>(r.stats.tets_added - r.stats.tets_removed);
    state.counters["nodes_added"] = static_cast<double>(r.stats.nodes_added);
    if (method == CutMethod::kSnap) {  // crossing edges snapping could not resolve
      SnapStats st;
      (void)snap_cut(f.pristine, b, {}, f.pristine_bvh->as_query(), &st);
      state.counters["snap_crossing_edges"] = static_cast<double>(st.crossing_edges);
      state.counters["snap_unresolved"] = static_cast<double>(st.edges_unresolved);
    }
  }
  run_cuts(state, f, b, method);
}
BENCHMARK(BM_Method)
    ->ArgsProduct({{0, 1, 2}, {0, 1}})
    ->Iterations(10)
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace serosa::cutting

BENCHMARK_MAIN();
