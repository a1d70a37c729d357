// The linear-solver strategy of the implicit step: A dv = b with A = M + dt C + dt^2 K_R,
// assembled (CHOLMOD always, CG unless matrix_free) or applied matrix-free, then solved directly
// or by CG with a Jacobi or CHOLMOD-factor preconditioner (fem/implicit_integrator.h).
#include <algorithm>
#include <cmath>
#include <utility>

#include "fem/block_system.h"
#include "fem/implicit_integrator.h"

namespace serosa::fem {

ImplicitIntegrator::SystemProduct ImplicitIntegrator::assemble_system(const TetMesh& mesh,
                                                                      double dt_s) {
  const SolverSettings& s = m_config.solver;
  SystemProduct a;
  // pcg_lagged factors the assembled double blocks (never float); matrix-free, it assembles them
  // only on the steps that factor (lagged_csr).
  const bool lagged = s.kind == SolverKind::pcg_lagged;
  if (s.matrix_free && s.kind != SolverKind::cholmod) {
    prepare_operator(mesh, m_el, dt_s, m_op);
    a.apply = [this, &mesh](std::span<const double> x, std::span<double> y) {
      apply_operator(mesh, m_el, m_pattern, m_rg, m_op, x, y);
    };
  } else if (s.kind == SolverKind::cholmod) {
    fill_system(mesh, m_el, m_pattern, m_rg, dt_s, m_a);
    a.apply = [this](std::span<const double> x, std::span<double> y) {
      multiply_system(m_pattern, m_a, x, y);
    };
  } else if (s.float_matrix && !lagged) {  // CG: 3x3 blocks (fem/block_system.h)
    m_blocks_f.resize(block_storage(m_pattern));
    fill_blocks<float>(mesh, m_el, m_pattern, m_rg, m_scale, dt_s, m_blocks_f, m_fill_scratch);
    a.apply_dot = [this](std::span<const double> x, std::span<double> y) {
      return multiply_blocks_dot<float>(m_pattern, m_blocks_f, x, y);
    };
  } else {
    m_blocks_d.resize(block_storage(m_pattern));
    fill_blocks<double>(mesh, m_el, m_pattern, m_rg, m_scale, dt_s, m_blocks_d, m_fill_scratch);
    m_blocks_fresh = true;
    a.apply_dot = [this](std::span<const double> x, std::span<double> y) {
      return multiply_blocks_dot<double>(m_pattern, m_blocks_d, x, y);
    };
  }
  return a;
}

SolveStatus ImplicitIntegrator::solve_system(const TetMesh& mesh, double dt_s,
                                             const SystemProduct& a, StepStatus& st) {
  if (m_config.solver.kind == SolverKind::cholmod) return solve_direct(a);
  return solve_cg(mesh, dt_s, a, st);
}

// CHOLMOD: symbolic analysis once per pattern, numeric factorization every step; the status
// carries the direct solve's residual and quadratic like CG's.
SolveStatus ImplicitIntegrator::solve_direct(const SystemProduct& a) {
  SolveStatus ss;
  if (!m_analyzed) m_analyzed = m_cholmod.analyze(m_a);
  if (!m_analyzed || !m_cholmod.factorize(m_a)) {
    ss.converged = false;
    ss.finite = false;
    return ss;
  }
  ss = m_cholmod.solve(m_rhs, m_b->dv);
  a.apply(m_b->dv, m_pcg.r);
  for (std::size_t i = 0; i < m_rhs.size(); ++i) m_pcg.r[i] = m_rhs[i] - m_pcg.r[i];
  const double rr = dot(m_pcg.r, m_pcg.r);
  const double bn = std::sqrt(dot(m_rhs, m_rhs));
  ss.residual = bn > 0.0 ? std::sqrt(rr) / bn : 0.0;
  double phi = 0.0;  // -dv.(b + r) / 2
  for (std::size_t i = 0; i < m_rhs.size(); ++i) phi -= 0.5 * m_b->dv[i] * (m_rhs[i] + m_pcg.r[i]);
  ss.energy = phi;
  ss.converged = ss.finite && ss.residual <= std::max(m_config.solver.tolerance, 1e-8);
  return ss;
}

SolveStatus ImplicitIntegrator::solve_cg(const TetMesh& mesh, double dt_s, const SystemProduct& a,
                                         StepStatus& st) {
  const SolverSettings& s = m_config.solver;
  const Preconditioner precond = cg_preconditioner(mesh, dt_s, st);
  const SolveStatus ss =
      a.apply_dot ? pcg(a.apply_dot, m_rhs, m_b->dv, s.tolerance, s.max_iterations, precond, m_pcg)
                  : pcg(a.apply, m_rhs, m_b->dv, s.tolerance, s.max_iterations, precond, m_pcg);
  if (s.kind == SolverKind::pcg_lagged) schedule_refresh(mesh, dt_s, ss.iterations, st);
  return ss;
}

void ImplicitIntegrator::fill_inverse_diagonal() {
  m_pcg.inv_diag.resize(m_rhs.size());
  const bool lagged = m_config.solver.kind == SolverKind::pcg_lagged;
  if (m_config.solver.matrix_free)
    operator_inverse_diagonal(m_el, m_pattern, m_rg, m_op, m_pcg.inv_diag);
  else if (m_config.solver.float_matrix && !lagged)
    blocks_inverse_diagonal<float>(m_pattern, m_blocks_f, m_pcg.inv_diag);
  else
    blocks_inverse_diagonal<double>(m_pattern, m_blocks_d, m_pcg.inv_diag);
}

Preconditioner ImplicitIntegrator::cg_preconditioner(const TetMesh& mesh, double dt_s,
                                                     StepStatus& st) {
  const SolverSettings& s = m_config.solver;
  Preconditioner precond;
  if (s.kind == SolverKind::pcg_cholmod) {
    // Rest-state factor P = M + dt C_0 + dt^2 K_0, computed in the background
    // (fem/background_factor.h): until it is ready for this structure, Jacobi; after a dt
    // change, the old factor until the new one is ready.
    m_factor.poll();
    CholmodSolver* factor = m_factor.factor_for(m_b->structure);
    if ((factor == nullptr || m_factor.factor_dt() != dt_s) &&
        !m_factor.requested(m_b->structure, dt_s)) {
      const auto m = static_cast<std::size_t>(mesh.num_tets());
      m_rg_rest.resize(4 * m);
      for (std::size_t t = 0; t < m; ++t)
        for (std::size_t c = 0; c < 4; ++c) m_rg_rest[4 * t + c] = m_el.elements[t].grad[c];
      CsrMatrix rest = m_a;
      fill_system(mesh, m_el, m_pattern, m_rg_rest, dt_s, rest);
      m_factor.request(std::move(rest), m_b->structure, dt_s, s.factor_delay_ms);
      if (!s.background_factor) m_factor.wait();
      factor = m_factor.factor_for(m_b->structure);
    }
    if (factor != nullptr) {
      precond.apply = [factor](std::span<const double> r, std::span<double> z) {
        factor->solve(r, z);
      };
      return precond;
    }
    st.factor_pending = true;
  }
  fill_inverse_diagonal();
  precond.inv_diag = m_pcg.inv_diag;
  if (s.kind == SolverKind::pcg_lagged) lagged_preconditioner(mesh, dt_s, st, precond);
  return precond;
}

void ImplicitIntegrator::lagged_preconditioner(const TetMesh& mesh, double dt_s, StepStatus& st,
                                               Preconditioner& precond) {
  m_lagged.begin_step(m_b->steps);
  st.factor_wait_ms = m_lagged.last_wait_ms();
  m_patch_for_change = m_patch_new = false;
  update_node_rotations(mesh);
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  update_free_mask(mesh);
  m_b->changed.resize(n, 1);  // new nodes are touched
  const bool stale = m_lagged.ready() && m_lagged.structure() != m_b->structure;
  if (m_lagged.ready() && !stale) std::fill(m_b->changed.begin(), m_b->changed.end(), 0);
  if (!m_lagged.ready() || (stale && !m_config.solver.patch_after_cut)) {
    // The first step, after a full rebuild (or after a cut without patching): factor this
    // step's matrix now.
    m_lagged.factor_now(lagged_csr(mesh, dt_s), m_b->structure, m_node_rot, m_b->q, m_free);
    st.factor_refresh = true;
  } else {
    // A cut since the installed factor, or nodes held or let go since: their rows get a factor
    // of their own; a refresh is asked for after the solve (schedule_refresh).
    m_kind_changed.resize(n);
    const bool kinds = m_lagged.kinds_changed(m_free, m_kind_changed);
    m_patch_for_change = stale || kinds;
    m_patch_new = m_patch_for_change && !m_lagged.patch_fits(m_b->structure, m_free);
    const Misfit misfit = m_config.solver.misfit_rad > 0.0 ? mark_misfit_nodes(mesh) : Misfit{};
    if (!m_patch_for_change && misfit.nodes == 0) {
      m_lagged.drop_patch();  // the installed factor fits again
    } else if (misfit.unpatched > 0 || m_patch_new) {
      if (stale)  // the cut's touched nodes too
        for (std::size_t i = 0; i < n; ++i) m_kind_changed[i] |= m_b->changed[i];
      patch_lagged_factor(mesh, dt_s, st);
    }
  }
  if (!m_lagged.ready()) return;
  m_warp.resize(n);
  m_lagged.warp(m_node_rot, m_warp);
  precond.apply = [this](std::span<const double> r, std::span<double> z) {
    m_lagged.apply(r, z, m_pcg.inv_diag, m_free, m_warp);
  };
}

// The patch in use is kept while it still fits (none of its tets turned since it was made) and
// solves every node the factor's warp no longer fits: the misfit lasts for tens of steps after a
// cut, and a patch made anew on each of them costs a factorization of hundreds of rows.
ImplicitIntegrator::Misfit ImplicitIntegrator::mark_misfit_nodes(const TetMesh& mesh) {
  const double cos_half = std::cos(0.5 * m_config.solver.misfit_rad);
  const int patch = mark_patch_misfit(mesh, cos_half);
  const Misfit factor = mark_factor_misfit(mesh, cos_half);
  return {patch + factor.nodes, patch + factor.unpatched};
}

// The patch is not warped: every node of a tet with a node in it that turned since the patch's
// step (a cut's fresh pieces recoil) calls for a new one.
int ImplicitIntegrator::mark_patch_misfit(const TetMesh& mesh, double cos_half) {
  if (!m_lagged.has_patch()) return 0;
  const std::span<const Quat> patch0 = m_lagged.patch_rotations();
  int marked = 0;
  for (std::size_t t = 0; t < std::min(m_b->q.size(), patch0.size()); ++t) {
    if (!m_el.elements[t].active()) continue;
    const Tet& nodes = mesh.tets[t];
    if (std::none_of(nodes.begin(), nodes.end(),
                     [&](std::int32_t i) { return m_lagged.patched(static_cast<std::size_t>(i)); }))
      continue;
    if (std::abs(m_b->q[t].dot(patch0[t])) >= cos_half) continue;
    ++marked;
    for (const std::int32_t i : nodes) m_kind_changed[static_cast<std::size_t>(i)] = 1;
  }
  return marked;
}

// A node whose tet turned otherwise than the node's warp W_i = R_i R0_i^T since the factor's step.
ImplicitIntegrator::Misfit ImplicitIntegrator::mark_factor_misfit(const TetMesh& mesh,
                                                                  double cos_half) {
  const std::span<const Quat> tet0 = m_lagged.tet_rotations();
  const std::span<const Quat> node0 = m_lagged.node_rotations();
  const std::size_t nw = std::min(node0.size(), m_node_rot.size());
  m_node_warp.resize(nw);  // each node's warp once, not once per corner
  for (std::size_t i = 0; i < nw; ++i) m_node_warp[i] = m_node_rot[i] * node0[i].conjugate();
  Misfit marked;
  for (std::size_t t = 0; t < std::min(m_b->q.size(), tet0.size()); ++t) {
    // Tets a cut added since the factor's step have no rotation of its (zero): a cut's patch
    // holds their nodes.
    if (!m_el.elements[t].active() || tet0[t].coeffs().squaredNorm() == 0.0) continue;
    const Quat turn = m_b->q[t] * tet0[t].conjugate();
    for (const std::int32_t i : mesh.tets[t]) {
      const auto u = static_cast<std::size_t>(i);
      if (u >= nw || m_kind_changed[u] != 0) continue;
      if (std::abs(turn.dot(m_node_warp[u])) >= cos_half) continue;
      m_kind_changed[u] = 1;
      ++marked.nodes;
      marked.unpatched += m_lagged.patched(u) ? 0 : 1;
    }
  }
  return marked;
}

// The patch: the changed nodes (m_kind_changed) and rings of neighbours around them, so that the
// patch's edge, where the old factor meets it, lies in rows that did not change.
void ImplicitIntegrator::patch_lagged_factor(const TetMesh& mesh, double dt_s, StepStatus& st) {
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  m_patch_nodes = m_kind_changed;
  for (std::int32_t ring = 0; ring < m_config.solver.patch_rings; ++ring) {
    m_ring_inner = m_patch_nodes;  // copies into kept capacity
    for (std::size_t i = 0; i < n; ++i)
      if (m_ring_inner[i] != 0)
        for (const std::int32_t j : m_pattern.nbr.of(i))
          m_patch_nodes[static_cast<std::size_t>(j)] = 1;
  }
  st.factor_patch =
      m_lagged.patch(patch_rows_csr(mesh, dt_s), m_b->structure, m_patch_nodes, m_free, m_b->q);
  if (!st.factor_patch) {
    m_lagged.factor_now(lagged_csr(mesh, dt_s), m_b->structure, m_node_rot, m_b->q, m_free);
    st.factor_refresh = true;
  }
}

// This step's A as the lagged factor takes it: the double blocks (filled now if the product was
// matrix-free) copied into m_a, once a step.
const CsrMatrix& ImplicitIntegrator::lagged_csr(const TetMesh& mesh, double dt_s) {
  if (!m_blocks_fresh) {
    m_blocks_d.resize(block_storage(m_pattern));
    fill_blocks<double>(mesh, m_el, m_pattern, m_rg, m_scale, dt_s, m_blocks_d, m_fill_scratch);
    m_blocks_fresh = true;
  }
  if (!m_csr_fresh) {
    blocks_to_csr<double>(m_pattern, m_blocks_d, m_a);
    m_csr_fresh = true;
  }
  return m_a;
}

// The patch reads only its own rows of A: those alone are filled (when the product did not fill
// them all) and copied (the whole matrix's fill, a millisecond of the step after a cut, waits for
// the refresh on the next step).
const CsrMatrix& ImplicitIntegrator::patch_rows_csr(const TetMesh& mesh, double dt_s) {
  if (m_csr_fresh) return m_a;
  if (!m_blocks_fresh) {
    m_blocks_d.resize(block_storage(m_pattern));
    fill_blocks<double>(mesh, m_el, m_pattern, m_rg, m_scale, dt_s, m_blocks_d, m_fill_scratch,
                        m_patch_nodes);
  }
  // Filled or not, only the patch's rows are copied: the whole copy took 4 ms on the step after
  // the hook's cut of the default scene (a refresh asked for later copies the rest).
  blocks_to_csr<double>(m_pattern, m_blocks_d, m_a, m_patch_nodes);
  return m_a;
}

// m_free: 1 where the node takes part in the solve (not fixed, not held, not massless).
void ImplicitIntegrator::update_free_mask(const TetMesh& mesh) {
  m_free.resize(static_cast<std::size_t>(mesh.num_nodes()));
  for (std::size_t i = 0; i < m_free.size(); ++i)
    m_free[i] = node_constrained(mesh, m_el, i) ? 0 : 1;
}

// A node's rotation: the normalized sum of its tets' rotations (quaternions turned into one
// hemisphere first), the identity for a node in no active tet.
void ImplicitIntegrator::update_node_rotations(const TetMesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  m_node_rot.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (const std::int32_t ic : m_pattern.incident_of(i)) {
      const auto t = static_cast<std::size_t>(ic) / 4;
      if (!m_el.elements[t].active()) continue;
      const Eigen::Vector4d q = m_b->q[t].coeffs();
      sum += sum.dot(q) < 0.0 ? Eigen::Vector4d(-q) : q;
    }
    const double norm = sum.norm();
    m_node_rot[i] = norm > 0.0 ? Quat(Eigen::Vector4d(sum / norm)) : Quat::Identity();
  }
}

void ImplicitIntegrator::schedule_refresh(const TetMesh& mesh, double dt_s, int iterations,
                                          StepStatus& st) {
  const SolverSettings& s = m_config.solver;
  if (m_lagged.pending()) return;  // one job at a time
  // A step that patched asks on the next one: the refresh takes the whole matrix, filled and
  // copied, which would double the cost of the step that already pays for the cut or the grasp.
  if (st.factor_patch && m_patch_new) return;
  // After a cut (the installed factor is of an older structure), a grasp or a release (a patch
  // in use) a refresh is due whatever the iterations: the patch only bridges the lag.
  const bool cut = m_lagged.structure() != m_b->structure;
  const bool patched = m_lagged.has_patch() && m_patch_for_change;
  if (!cut && !patched && iterations <= s.refresh_iterations) return;
  // Urgent: a solve that needed several times the usual iterations (a sudden turn), or a grasp or
  // a release (patched, still a few times the usual while the jaws pull). After a cut the refresh
  // needs a new symbolic analysis too and gets a longer lag (cut_lag_steps): at the urgent one,
  // and at the usual one on the default scene, the step that installed it waited for the
  // background thread.
  const bool urgent = !cut && (patched || iterations > 3 * s.refresh_iterations);
  const int lag = urgent ? std::min(s.urgent_lag_steps, s.factor_lag_steps)
                  : cut  ? std::max(s.cut_lag_steps, s.factor_lag_steps)
                         : s.factor_lag_steps;
  m_lagged.request(lagged_csr(mesh, dt_s), m_b->structure,
                   m_b->steps + static_cast<std::uint64_t>(std::max(lag, 1)), s.background_factor,
                   m_node_rot, m_b->q, m_free);
  st.factor_refresh = true;
}

}  // namespace serosa::fem
