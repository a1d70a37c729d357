// Cost of a topology change for the FEM: ImplicitIntegrator::update (local: elements, masses and
// the matrix pattern around the cut, fem/system_matrix.h update_pattern) against a full
// rebuild(), after one small real scissor cut (serosa::cutting, linked into this benchmark only)
// on boxes of growing size: the gmsh SOFA boxes (19k, 95k tets) and a structured 165k box.
// The blade is a square about two element sizes wide at a random place in the box, so every
// size sees a cut of similar tet count; each iteration makes a new cut (cutting and apply() are
// not timed), and times update() or rebuild() only. Solver: CG (no direct factor to redo).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>

#include "box_scene.h"
#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/topology_delta.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem::bench {
namespace {

TetMesh box_by_name(const std::string& name) {
  if (name == "box_165k") return structured_box(19);
  return asset_box(name + ".msh");
}

// A small random cut of m: a square blade of half-width ~ one element size, random normal.
TopologyDelta small_cut(const TetMesh& m, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = std::cbrt(24.0 / m.num_tets());  // cube side of a 6-tet cube, m
  const Vec3 c(2.0 + 1.5 * u(rng), 0.3 * u(rng), 0.3 * u(rng));
  const Vec3 n = Vec3(u(rng), u(rng), u(rng) + 1.5).normalized();
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  const double r = 1.0 * h;
  const cutting::ConvexPolygon blade(
      {c - r * a - r * b, c + r * a - r * b, c + r * a + r * b, c - r * a + r * b});
  return cutting::cut_mesh(m, blade).delta;
}

void topology_bench(benchmark::State& state, const std::string& name, bool local) {
  TetMesh m = box_by_name(name);
  ImplicitIntegrator integ(box_config(SolverKind::pcg, 1e-12, 20));
  integ.step(m, kBoxDt);
  std::mt19937 rng(17);
  double changed = 0.0, rows = 0.0, blocks = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    TopologyDelta d = small_cut(m, rng);
    apply(m, d);
    changed += static_cast<double>(d.removed_tets.size() + d.added_tets.size());
    state.ResumeTiming();
    if (local)
      integ.update(m, d);
    else
      integ.rebuild(m);
    state.PauseTiming();
    rows += integ.last_update().rows_rewritten;
    blocks += integ.last_update().blocks_updated;
    state.ResumeTiming();
  }
  const auto it = static_cast<double>(state.iterations());
  state.counters["tets"] = m.num_tets();
  state.counters["tets_cut"] = changed / it;  // removed + added per cut
  if (local) {
    state.counters["rows"] = rows / it;
    state.counters["blocks"] = blocks / it;
  }
}

void register_all() {
  for (const char* name : {"box_19k", "box_95k", "box_165k"}) {
    benchmark::RegisterBenchmark((std::string("BM_CutUpdate/local/") + name).c_str(),
                                 topology_bench, name, true)
        ->Unit(benchmark::kMicrosecond)
        ->Iterations(30);
    benchmark::RegisterBenchmark((std::string("BM_CutUpdate/rebuild/") + name).c_str(),
                                 topology_bench, name, false)
        ->Unit(benchmark::kMicrosecond)
        ->Iterations(5);
  }
}

const bool registered = (register_all(), true);

}  // namespace
}  // namespace serosa::fem::bench
