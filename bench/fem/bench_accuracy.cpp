// Accuracy against time on the SOFA-matching box (box_scene.h): 100 steps (1 s) for each solver
// setting, reporting ms per step, the displacement error relative to a converged reference
// (CHOLMOD, same steps) and the free end's sag after 1 s. Error = max_i |x_i - x_ref,i| /
// max_i |x_ref,i - X_i| (relative to the largest displacement). Each benchmark runs once
// (Iterations(1)): one run is 100 steps. CHOLMOD is the reference itself (error 0); its time per
// step is BM_StepCholmod's.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "box_scene.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem::bench {
namespace {

using serosa::bench::relative_displacement_error;
using serosa::bench::run_timed_steps;
using serosa::bench::TimedRun;

constexpr int kSteps = 100;  // 1 s at dt = 0.01 s

struct Run {
  TetMesh mesh;
  double ms_per_step = 0.0;
  int not_converged = 0;
  int rejected = 0;
};

Run simulate_mesh(TetMesh mesh, FemConfig cfg);

Run simulate(int k, FemConfig cfg) { return simulate_mesh(structured_box(k), std::move(cfg)); }

Run simulate_mesh(TetMesh mesh, FemConfig cfg) {
  Run r{std::move(mesh)};
  const TimedRun t = run_timed_steps(r.mesh, std::move(cfg), kSteps, kBoxDt);
  r.ms_per_step = t.ms_per_step;
  r.not_converged = t.not_converged;
  r.rejected = t.rejected;
  return r;
}

// The converged reference of box k (CHOLMOD), computed once per process.
const TetMesh& reference(int k) {
  static std::map<int, TetMesh> cache;
  auto it = cache.find(k);
  if (it == cache.end())
    it = cache.emplace(k, simulate(k, box_config(SolverKind::cholmod, 1e-12, 0)).mesh).first;
  return it->second;
}

double relative_error(const TetMesh& m, const TetMesh& ref) {
  return relative_displacement_error(m, ref);
}

void accuracy(benchmark::State& state, SolverKind kind, double tol, int cap,
              bool float_matrix = false) {
  const int k = static_cast<int>(state.range(0));
  const TetMesh& ref = reference(k);
  Run r;
  for (auto _ : state) {
    FemConfig cfg = box_config(kind, tol, cap);
    cfg.solver.float_matrix = float_matrix;
    r = simulate(k, std::move(cfg));
  }
  state.counters["tets"] = r.mesh.num_tets();
  state.counters["ms/step"] = r.ms_per_step;
  state.counters["steps/s"] = 1000.0 / r.ms_per_step;
  state.counters["error"] = relative_error(r.mesh, ref);
  state.counters["sag_1s"] = free_end_sag(r.mesh);
  state.counters["ref_sag_1s"] = free_end_sag(ref);
  state.counters["unconverged"] = r.not_converged;
  state.counters["rejected"] = r.rejected;
}

// No reference: the 95k box (k = 16) with CG capped at 20 and 100 iterations, sag after 1 s.
void box_only(benchmark::State& state, SolverKind kind, double tol, int cap) {
  const int k = static_cast<int>(state.range(0));
  Run r;
  for (auto _ : state) r = simulate(k, box_config(kind, tol, cap));
  state.counters["tets"] = r.mesh.num_tets();
  state.counters["ms/step"] = r.ms_per_step;
  state.counters["steps/s"] = 1000.0 / r.ms_per_step;
  state.counters["sag_1s"] = free_end_sag(r.mesh);
  state.counters["unconverged"] = r.not_converged;
}

// The gmsh boxes of config/sofa_box*.toml (assets/box_19k.msh, box_95k.msh).
void gmsh_box(benchmark::State& state, const char* asset, double tol, int cap) {
  Run r;
  for (auto _ : state) r = simulate_mesh(asset_box(asset), box_config(SolverKind::pcg, tol, cap));
  state.counters["tets"] = r.mesh.num_tets();
  state.counters["ms/step"] = r.ms_per_step;
  state.counters["steps/s"] = 1000.0 / r.ms_per_step;
  state.counters["sag_1s"] = free_end_sag(r.mesh);
  state.counters["unconverged"] = r.not_converged;
}

void register_all() {
  for (const char* asset : {"box_19k.msh", "box_95k.msh"}) {
    benchmark::RegisterBenchmark("BM_GmshBox/cap20", gmsh_box, asset, 0.0, 20)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_GmshBox/tol1e-2", gmsh_box, asset, 1e-2, 1000)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  }
  for (int cap : {20, 100})
    benchmark::RegisterBenchmark("BM_Box/pcg_cap", box_only, SolverKind::pcg, 0.0, cap)
        ->Arg(16)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  for (int k : {9}) {
    for (double tol : {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8})
      benchmark::RegisterBenchmark("BM_Accuracy/pcg_tol", accuracy, SolverKind::pcg, tol, 1000,
                                   false)
          ->Arg(k)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    // The same with float blocks (SolverSettings::float_matrix): the error it adds.
    for (double tol : {1e-2, 1e-4, 1e-6, 1e-8})
      benchmark::RegisterBenchmark("BM_Accuracy/pcg_tol_float", accuracy, SolverKind::pcg, tol,
                                   1000, true)
          ->Arg(k)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    for (int cap : {20, 100})
      benchmark::RegisterBenchmark("BM_Accuracy/pcg_cap_float", accuracy, SolverKind::pcg, 0.0, cap,
                                   true)
          ->Arg(k)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    for (int cap : {5, 10, 20, 50, 100, 200})
      benchmark::RegisterBenchmark("BM_Accuracy/pcg_cap", accuracy, SolverKind::pcg, 0.0, cap,
                                   false)
          ->Arg(k)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
    for (int cap : {5, 10, 20})
      benchmark::RegisterBenchmark("BM_Accuracy/pcg_cholmod_cap", accuracy, SolverKind::pcg_cholmod,
                                   0.0, cap, false)
          ->Arg(k)
          ->Iterations(1)
          ->Unit(benchmark::kMillisecond);
  }
}

const bool registered = (register_all(), true);

}  // namespace
}  // namespace serosa::fem::bench
