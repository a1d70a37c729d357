// ms per implicit step against mesh size (structured 4 x 1 x 1 boxes, 1.5k..165k tets) for each
// solver: PCG (Jacobi) capped at 20 iterations, assembled and matrix-free, PCG preconditioned by
// the rest-state CHOLMOD factor (20 iterations), and CHOLMOD (factorization every step); CG with
// float blocks (SolverSettings::float_matrix); and the gmsh boxes the speed targets are set on.
#include <benchmark/benchmark.h>

#include "box_scene.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem::bench {
namespace {

void step_on(benchmark::State& state, TetMesh m, SolverKind kind, int iterations, bool matrix_free,
             bool float_matrix) {
  FemConfig cfg = box_config(kind, 1e-12, iterations);
  cfg.solver.matrix_free = matrix_free;
  cfg.solver.float_matrix = float_matrix;
  ImplicitIntegrator integ(cfg);
  integ.step(m, kBoxDt);        // precompute, analysis, first factorization
  integ.wait_for_background();  // pcg_cholmod: time the steps with the factor ready
  int applied = 0;
  for (auto _ : state) applied += integ.step(m, kBoxDt).applied ? 1 : 0;
  state.counters["tets"] = m.num_tets();
  state.counters["steps/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["applied"] = applied;
}

void step_bench(benchmark::State& state, SolverKind kind, int iterations, bool matrix_free = false,
                bool float_matrix = false) {
  step_on(state, structured_box(static_cast<int>(state.range(0))), kind, iterations, matrix_free,
          float_matrix);
}

// The gmsh boxes of the speed targets (assets/box_19k.msh: 19,091 tets, >= 200 steps/s;
// box_95k.msh: 95,571, >= 40 steps/s), CG capped at 20 iterations, double or float blocks.
void BM_StepGmsh19k(benchmark::State& s) {
  step_on(s, asset_box("box_19k.msh"), SolverKind::pcg, 20, false, s.range(0) != 0);
}
void BM_StepGmsh95k(benchmark::State& s) {
  step_on(s, asset_box("box_95k.msh"), SolverKind::pcg, 20, false, s.range(0) != 0);
}
BENCHMARK(BM_StepGmsh19k)->ArgName("float")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StepGmsh95k)->ArgName("float")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_StepPcg20(benchmark::State& s) { step_bench(s, SolverKind::pcg, 20); }
void BM_StepPcg20Float(benchmark::State& s) { step_bench(s, SolverKind::pcg, 20, false, true); }
void BM_StepPcg20MatrixFree(benchmark::State& s) { step_bench(s, SolverKind::pcg, 20, true); }
void BM_StepPcgCholmod20(benchmark::State& s) { step_bench(s, SolverKind::pcg_cholmod, 20); }
void BM_StepCholmod(benchmark::State& s) { step_bench(s, SolverKind::cholmod, 0); }

// k: 4k x k x k cubes, 24 k^3 tets: 4 -> 1.5k, 6 -> 5.2k, 9 -> 17.5k, 12 -> 41k, 16 -> 98k,
// 19 -> 165k.
BENCHMARK(BM_StepPcg20)
    ->Arg(4)
    ->Arg(6)
    ->Arg(9)
    ->Arg(12)
    ->Arg(16)
    ->Arg(19)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StepPcg20Float)
    ->Arg(4)
    ->Arg(6)
    ->Arg(9)
    ->Arg(12)
    ->Arg(16)
    ->Arg(19)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StepPcg20MatrixFree)
    ->Arg(4)
    ->Arg(6)
    ->Arg(9)
    ->Arg(12)
    ->Arg(16)
    ->Arg(19)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StepPcgCholmod20)
    ->Arg(4)
    ->Arg(6)
    ->Arg(9)
    ->Arg(12)
    ->Arg(16)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StepCholmod)->Arg(4)->Arg(6)->Arg(9)->Arg(12)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace serosa::fem::bench
