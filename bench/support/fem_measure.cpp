#include "bench/support/fem_measure.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <stdexcept>
#include <utility>

#include "engine/kuhn_grid.h"
#include "fem/implicit_integrator.h"

namespace serosa::bench {

using fem::FemConfig;
using fem::ImplicitIntegrator;
using fem::StepStatus;

TetMesh structured_bar(int nx, int ny, int nz, double lx, double ly, double lz) {
  if (nx < 1 || ny < 1 || nz < 1) throw std::invalid_argument("structured_bar: needs >= 1 box");
  const double hx = lx / nx, hy = ly / ny, hz = lz / nz;
  TetMesh m = kuhn_grid(KuhnGridSpec{kuhn_axis(nx, hx),
                                     kuhn_axis(ny, hy, -0.5 * ly),
                                     kuhn_axis(nz, hz, -0.5 * lz),
                                     KuhnOrder::kXFastest,
                                     {}});
  m.fill_node_state();
  for (std::size_t i = 0; i < m.rest.size(); ++i) m.fixed[i] = m.rest[i].x() < 1e-9 * lx ? 1 : 0;
  return m;
}

TimedRun run_timed_steps(TetMesh& mesh, FemConfig cfg, int steps, double dt_s) {
  cfg.solver.background_factor = false;
  ImplicitIntegrator integ(cfg);
  integ.rebuild(mesh);
  TimedRun r;
  double ms = 0.0;
  for (int s = 0; s < steps; ++s) {
    const auto t0 = std::chrono::steady_clock::now();
    const StepStatus st = integ.step(mesh, dt_s);
    ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r.not_converged += st.converged ? 0 : 1;
    r.rejected += st.applied ? 0 : 1;
  }
  r.ms_per_step = steps > 0 ? ms / steps : 0.0;
  return r;
}

double relative_displacement_error(const TetMesh& m, const TetMesh& ref) {
  if (m.x.size() != ref.x.size())
    throw std::invalid_argument("relative_displacement_error: meshes differ in node count");
  double err = 0.0, disp = 0.0;
  for (std::size_t i = 0; i < m.x.size(); ++i) {
    err = std::max(err, (m.x[i] - ref.x[i]).norm());
    disp = std::max(disp, (ref.x[i] - ref.rest[i]).norm());
  }
  return disp > 0.0 ? err / disp : err;
}

double free_end_sag(const TetMesh& m, double x_end) {
  double s = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < m.rest.size(); ++i)
    if (m.rest[i].x() >= x_end - 1e-6) {
      s += m.rest[i].y() - m.x[i].y();
      ++n;
    }
  return n > 0 ? s / n : 0.0;
}

}  // namespace serosa::bench
