// The lagged factor's refresh (fem/lagged_factor.h), what the background thread does each time:
// the numeric factorization of the system matrix A = M + dt C + dt^2 K_R (its analysis kept), the
// export of the factor and its 3x3 float blocks (fem/block_factor.h). The node-blocked layout
// (supernodal L L^T through BLAS) against CHOLMOD's simplicial LDL^T (column by column, no BLAS),
// on the structured boxes (k = 4: 1.5k tets, k = 6: 5.2k, about the default scene's 4.8k; k = 9:
// 17.5k) and the gmsh 19k box. Which BLAS CHOLMOD calls is the system's (Debian's alternatives):
// run it once with each to compare them.
#include <benchmark/benchmark.h>
#include <omp.h>

#include "box_scene.h"
#include "fem/block_factor.h"
#include "fem/cholmod_solver.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem::bench {
namespace {

// A of the box after one step under gravity (its rotations near the identity: the values do not
// change the factorization's cost).
CsrMatrix box_matrix(TetMesh m) {
  ImplicitIntegrator integ(box_config(SolverKind::cholmod, 1e-12, 1));
  integ.step(m, kBoxDt);
  return integ.assembled_matrix();
}

void refresh_on(benchmark::State& state, const CsrMatrix& a) {
  omp_set_num_threads(1);  // as on the refresh's own thread (fem/lagged_factor.cpp)
  const bool blocks = state.range(1) != 0;
  CholmodSolver chol(blocks ? CholmodSolver::Layout::node_blocks
                            : CholmodSolver::Layout::simplicial);
  if (!chol.analyze(a)) {
    state.SkipWithError("analysis failed");
    return;
  }
  LdlFactor ldl;
  BlockFactor block;
  for (auto _ : state) {
    bool ok = chol.factorize(a);
    if (blocks) ok = ok && chol.export_ldl(ldl) && block.build(ldl);
    if (!ok) {
      state.SkipWithError("factorization failed");
      return;
    }
  }
  state.counters["rows"] = a.rows;
}

void BM_FactorRefresh(benchmark::State& s) {
  refresh_on(s, box_matrix(structured_box(static_cast<int>(s.range(0)))));
}
void BM_FactorRefreshGmsh19k(benchmark::State& s) {
  refresh_on(s, box_matrix(asset_box("box_19k.msh")));
}
// (k or 0, node_blocks): node_blocks 1 is the lagged factor's refresh, 0 CHOLMOD's simplicial.
BENCHMARK(BM_FactorRefresh)
    ->ArgNames({"k", "node_blocks"})
    ->ArgsProduct({{4, 6, 9}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FactorRefreshGmsh19k)
    ->ArgNames({"k", "node_blocks"})
    ->ArgsProduct({{0}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace serosa::fem::bench
