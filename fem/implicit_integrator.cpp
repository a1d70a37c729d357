#include "fem/implicit_integrator.h"
#include "fem/parallel.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "engine/stage.h"
#include "fem/block_system.h"
#include "fem/elastic_forces.h"
#include "fem/rotation.h"

namespace serosa::fem {

ImplicitIntegrator::ImplicitIntegrator(FemConfig config) : m_config(std::move(config)) {
  m_lagged.bind(m_b->lagged);  // its own schedule until a state's block is bound
}

void ImplicitIntegrator::rebuild_solver_structure(const TetMesh& mesh) {
  build_pattern(mesh, m_pattern, m_a);
  const auto n3 = static_cast<std::size_t>(3 * mesh.num_nodes());
  m_rhs.assign(n3, 0.0);
  m_pcg.r.assign(n3, 0.0);
  m_b->dv.resize(n3, 0.0);
  m_fe.resize(4 * static_cast<std::size_t>(mesh.num_tets()));
  m_rot.resize(static_cast<std::size_t>(mesh.num_tets()), Mat3::Identity());
  m_rg.resize(4 * static_cast<std::size_t>(mesh.num_tets()));
  m_analyzed = false;
  ++m_b->structure;
  if (m_config.solver.kind == SolverKind::cholmod) m_analyzed = m_cholmod.analyze(m_a);
}

namespace {

// Capacity beyond the current count that a rebuild leaves in per-tet and per-node arrays, so that
// the tets and nodes later cuts append (update()) do not reallocate and copy whole arrays (a copy
// of every per-tet array costs more than the local update itself on 100k+ tets). Reserved but
// untouched memory costs no page faults.
constexpr double kCutSpare = 0.5;

template <class T>
void reserve_spare(std::vector<T>& v, std::size_t count) {
  v.reserve(count + static_cast<std::size_t>(kCutSpare * static_cast<double>(count)));
}

}  // namespace

void ImplicitIntegrator::reserve_for_cuts(TetMesh& mesh) {
  const auto m = static_cast<std::size_t>(mesh.num_tets());
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  reserve_spare(m_el.elements, m);
  reserve_spare(m_el.node_mass, n);
  reserve_spare(m_el.node_damping, n);
  reserve_spare(mesh.mass, n);
  reserve_spare(m_b->q, m);
  reserve_spare(m_b->q_prev, m);
  reserve_spare(m_rot, m);
  reserve_spare(m_scale, m);
  reserve_spare(m_rg, 4 * m);
  reserve_spare(m_fe, 4 * m);
  for (std::vector<double>* v : {&m_rhs, &m_b->dv, &m_pcg.r, &m_pcg.z, &m_pcg.p, &m_pcg.ap})
    reserve_spare(*v, 3 * n);
}

void ImplicitIntegrator::rebuild(TetMesh& mesh) {
  mesh.fill_node_state();
  build_elements(mesh, m_config, m_el);
  mesh.mass = m_el.node_mass;
  m_b->q.assign(static_cast<std::size_t>(mesh.num_tets()), Quat::Identity());
  m_b->q_prev = m_b->q;
  m_b->plastic.clear();
  m_b->dv.assign(3 * static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  m_rot.assign(static_cast<std::size_t>(mesh.num_tets()), Mat3::Identity());
  m_lagged.clear();
  m_b->changed.clear();
  rebuild_solver_structure(mesh);
  reserve_for_cuts(mesh);
  m_b->node_damping = m_el.node_damping;
  m_b->built = true;
  m_b->energy_pending = false;
}

void ImplicitIntegrator::prepare(TetMesh& mesh, double dt_s) {
  rebuild(mesh);
  if (m_config.solver.kind != SolverKind::pcg_lagged) return;
  // The next step's own matrix: its element pass and assembly, without keeping what they change
  // of the warm starts (the step redoes them from the same start).
  const std::vector<Quat> q = m_b->q, q_prev = m_b->q_prev;
  if (m_config.plasticity.on) m_b->plastic.resize(mesh.tets.size(), Mat3::Zero());
  m_blocks_fresh = m_csr_fresh = false;
  (void)element_pass(mesh, dt_s);
  (void)assemble_system(mesh, dt_s);
  update_node_rotations(mesh);
  update_free_mask(mesh);
  m_lagged.factor_now(lagged_csr(mesh, dt_s), m_b->structure, m_node_rot, m_b->q, m_free);
  m_lagged.warm_up();
  m_b->q = q;
  m_b->q_prev = q_prev;
}

void ImplicitIntegrator::update(TetMesh& mesh, const TopologyDelta& delta) {
  if (!m_b->built || m_el.topology_version != delta.version_before ||
      m_pattern.topology_version != delta.version_before ||
      mesh.topology_version != delta.version_after || m_el.elements.size() != m_b->q.size()) {
    rebuild(mesh);
    return;
  }
  // The removed tets' nodes, before their elements are overwritten (the mesh no longer has them).
  m_removed.clear();
  for (std::int32_t r : delta.removed_tets)
    m_removed.push_back(m_el.elements[static_cast<std::size_t>(r)].nodes);
  const std::int64_t debris_before = m_el.debris_tets;
  update_elements(mesh, delta, m_config, m_el);
  // Masses of touched nodes only (new nodes appended); all of them when the cut left debris.
  if (m_el.debris_tets != debris_before) mesh.mass = m_el.node_mass;
  mesh.mass.resize(m_el.node_mass.size());
  for (const Tet& t : m_removed)
    for (std::int32_t i : t)
      mesh.mass[static_cast<std::size_t>(i)] = m_el.node_mass[static_cast<std::size_t>(i)];
  for (std::int32_t slot : delta.slot_of_added)
    for (std::int32_t i : mesh.tets[static_cast<std::size_t>(slot)])
      mesh.mass[static_cast<std::size_t>(i)] = m_el.node_mass[static_cast<std::size_t>(i)];
  // Per-tet rotations follow the same slot rules; added tets start from their SVD polar factor.
  for (std::size_t k = 0; k < delta.slot_of_added.size(); ++k) {
    const auto slot = static_cast<std::size_t>(delta.slot_of_added[k]);
    if (slot >= m_b->q.size()) {
      m_b->q.resize(slot + 1);
      m_b->q_prev.resize(slot + 1);
    }
    const TetElement& e = m_el.elements[slot];
    const Tet& n = mesh.tets[slot];
    m_b->q[slot] = e.active() ? Quat(polar_rotation_svd(nodal_gradient(
                                    e, mesh.x[n[0]], mesh.x[n[1]], mesh.x[n[2]], mesh.x[n[3]])))
                              : Quat::Identity();
    m_b->q_prev[slot] = m_b->q[slot];  // no rotation rate yet
  }
  for (const auto& [from, to] : delta.moved_tets) {
    m_b->q[static_cast<std::size_t>(to)] = m_b->q[static_cast<std::size_t>(from)];
    m_b->q_prev[static_cast<std::size_t>(to)] = m_b->q_prev[static_cast<std::size_t>(from)];
  }
  m_b->q.resize(static_cast<std::size_t>(mesh.num_tets()));
  m_b->q_prev.resize(static_cast<std::size_t>(mesh.num_tets()));
  // Plastic strain follows the same slots; new tets start without any.
  if (!m_b->plastic.empty()) {
    for (std::int32_t slot : delta.slot_of_added) {
      if (static_cast<std::size_t>(slot) >= m_b->plastic.size())
        m_b->plastic.resize(static_cast<std::size_t>(slot) + 1);
      m_b->plastic[static_cast<std::size_t>(slot)].setZero();
    }
    for (const auto& [from, to] : delta.moved_tets)
      m_b->plastic[static_cast<std::size_t>(to)] = m_b->plastic[static_cast<std::size_t>(from)];
    m_b->plastic.resize(static_cast<std::size_t>(mesh.num_tets()), Mat3::Zero());
  }
  m_lagged.relabel_tets(delta, static_cast<std::size_t>(mesh.num_tets()));
  // The nodes whose rows of A the cut changed (the lagged factor's patch, fem/lagged_factor.h).
  m_b->changed.resize(static_cast<std::size_t>(mesh.num_nodes()), 1);
  for (const Tet& t : m_removed)
    for (std::int32_t i : t) m_b->changed[static_cast<std::size_t>(i)] = 1;
  for (std::int32_t slot : delta.slot_of_added)
    for (std::int32_t i : mesh.tets[static_cast<std::size_t>(slot)])
      m_b->changed[static_cast<std::size_t>(i)] = 1;
  // Matrix pattern: only the rows of touched nodes and the blocks of tets around them.
  m_last_update = update_pattern(mesh, delta, m_removed, m_pattern, m_a);
  // Per-node and per-tet work arrays grow or shrink at their ends (new nodes: no warm start).
  const auto n3 = 3 * static_cast<std::size_t>(mesh.num_nodes());
  const auto m = static_cast<std::size_t>(mesh.num_tets());
  m_rhs.resize(n3, 0.0);
  m_pcg.r.resize(n3, 0.0);
  m_b->dv.resize(n3, 0.0);
  m_fe.resize(4 * m);
  m_rot.resize(m, Mat3::Identity());
  m_rg.resize(4 * m);
  // A direct factor is global: CHOLMOD re-analyzes the new pattern; pcg_cholmod's background
  // factor is requested for the new structure by the next step.
  m_analyzed = false;
  ++m_b->structure;
  if (m_config.solver.kind == SolverKind::cholmod) m_analyzed = m_cholmod.analyze(m_a);
  m_b->energy_pending = false;  // the cut changed the energy: no balance across it
  m_b->node_damping = m_el.node_damping;
}

void ImplicitIntegrator::adopt(TetMesh& mesh) {
  if (!m_b->built) return;  // restored from before its first step: nothing built yet
  FemBlock saved = std::move(*m_b);
  const std::vector<double> mass = std::move(mesh.mass);
  rebuild(mesh);  // the caches; it rewrites the block, which the saved one then replaces
  *m_b = std::move(saved);
  m_lagged.bind(m_b->lagged);
  const auto m = static_cast<std::size_t>(mesh.num_tets());
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  const FemBlock& b = *m_b;
  if (b.q.size() != m || b.q_prev.size() != m || b.dv.size() != 3 * n ||
      (!b.plastic.empty() && b.plastic.size() != m) || mass.size() != n ||
      b.node_damping.size() != n || b.changed.size() > n)
    throw BlockMismatch("the FEM state does not fit the mesh (" + std::to_string(m) + " tets, " +
                        std::to_string(n) + " nodes)");
  mesh.mass = mass;  // as the cuts left them, not as the rebuild summed them
  m_el.node_mass = mass;
  m_el.node_damping = b.node_damping;
  if (!m_lagged.adopt(m_config.solver.background_factor))
    throw BlockMismatch("a matrix of the lagged factor's schedule is not SPD");
  if (m_lagged.rows_needed() > 3 * static_cast<std::int64_t>(n))
    throw BlockMismatch("the lagged factor's matrices do not fit the mesh (" + std::to_string(n) +
                        " nodes)");
}

StepStatus ImplicitIntegrator::step(TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext) {
  const StepStatus st = step_from(mesh, dt_s, f_ext, m_config.solver.remove_energy_gain);
  ++m_b->steps;
  return st;
}

// One step as its stages: the per-tet pass, the right-hand side, the energy guard (which may
// slow the state and take the step again), the system, the solve, the update.
StepStatus ImplicitIntegrator::step_from(TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext,
                                         bool may_remove) {
  if (m_el.topology_version != mesh.topology_version ||
      m_el.elements.size() != static_cast<std::size_t>(mesh.num_tets()) ||
      m_el.node_mass.size() != static_cast<std::size_t>(mesh.num_nodes()) ||
      m_pattern.topology_version != mesh.topology_version)
    rebuild(mesh);
  StepStatus st;
  m_blocks_fresh = m_csr_fresh = false;
  if (m_config.plasticity.on) m_b->plastic.resize(mesh.tets.size(), Mat3::Zero());
  const ElementPass pass = element_pass(mesh, dt_s);
  st.inverted_tets = pass.inverted;
  st.turned_tets = pass.turned;
  const double kinetic_j = assemble_rhs(mesh, dt_s, f_ext);
  check_energy_balance(pass, kinetic_j, st);
  if (st.energy_gain && may_remove && kinetic_j > 0.0) {
    // Take the gain out of the kinetic energy and run the step from the slowed state (the
    // forces above used v).
    const double s = std::sqrt(std::max(0.0, 1.0 - st.energy_change_j / kinetic_j));
    for (Vec3& v : mesh.v) v *= s;
    StepStatus again = step_from(mesh, dt_s, f_ext, false);
    again.energy_gain = true;
    again.converged = false;
    again.energy_j = st.energy_j;
    again.energy_change_j = st.energy_change_j;
    again.energy_removed_j = (1.0 - s * s) * kinetic_j;
    return again;
  }

  if (!m_config.solver.warm_start) std::fill(m_b->dv.begin(), m_b->dv.end(), 0.0);
  const SystemProduct a = assemble_system(mesh, dt_s);
  const SolveStatus ss = solve_system(mesh, dt_s, a, st);
  st.converged = ss.converged && !st.energy_gain;
  st.solve_converged = ss.converged;
  st.iterations = ss.iterations;
  st.residual = ss.residual;
  if (ss.residual > 1.0) {  // worse than dv = 0 in the residual norm
    st.residual_growth = true;
    st.converged = st.solve_converged = false;
  }
  // Never apply a non-finite or diverged solution (worse than dv = 0: phi > 0).
  if (!ss.finite || !std::isfinite(ss.residual) || !(ss.energy <= 0.0)) {
    std::fill(m_b->dv.begin(), m_b->dv.end(), 0.0);
    st.applied = false;
    st.converged = st.solve_converged = false;
    return st;
  }
  const double work_j = apply_update(mesh, dt_s, f_ext);
  // The energy balance of this step is checked at the start of the next one (divergence guard:
  // StepStatus::energy_gain), where the rotations of x' come for free.
  m_b->energy_before = kinetic_j + pass.elastic_j;
  m_b->energy_work = work_j;
  m_b->energy_pending = true;
  if (m_config.plasticity.on) update_plasticity(mesh, dt_s);
  st.applied = true;
  return st;
}

ImplicitIntegrator::ElementPass ImplicitIntegrator::element_pass(const TetMesh& mesh, double dt_s) {
  const std::int32_t m = mesh.num_tets();
  const bool plastic = m_config.plasticity.on;
  m_scale.resize(static_cast<std::size_t>(m));
  int inverted = 0;
  int turned = 0;
  double elastic = 0.0;
  double stiffness_volume = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : inverted, turned, elastic, stiffness_volume) if (m >= kParallelMin)
  for (std::int32_t t = 0; t < m; ++t) {
    const auto ut = static_cast<std::size_t>(t);
    const TetElement& e = m_el.elements[ut];
    std::span<Vec3, 4> out(m_fe.data() + 4 * ut, 4);
    if (!e.active()) {
      m_rot[ut].setIdentity();
      m_scale[ut] = {0.0, 0.0};
      for (std::size_t c = 0; c < 4; ++c) {
        out[c].setZero();
        m_rg[4 * ut + c].setZero();
      }
      continue;
    }
    stiffness_volume += (e.lambda_pa + 2.0 * e.mu_pa) * e.volume_m3;
    const Tet& nd = mesh.tets[ut];
    const Mat3 f = nodal_gradient(e, mesh.x[nd[0]], mesh.x[nd[1]], mesh.x[nd[2]], mesh.x[nd[3]]);
    if (f.determinant() <= 0.0) ++inverted;
    if (m_config.corotational) {
      // Warm-started from the last steps' rotations (fem/rotation.h step_rotation).
      Quat& q = m_b->q[ut];
      const Quat last = q;
      m_rot[ut] = step_rotation(f, q, m_b->q_prev[ut], kStepRotationTolerance);
      m_b->q_prev[ut] = last;
      if (std::abs(q.dot(last)) < kTurnedCosHalf) ++turned;
    } else {
      m_rot[ut].setIdentity();
    }
    for (std::size_t c = 0; c < 4; ++c) m_rg[4 * ut + c] = m_rot[ut] * e.grad[c];
    m_scale[ut] = tet_scale(e, dt_s);
    const Mat3 fv = nodal_gradient(e, mesh.v[nd[0]], mesh.v[nd[1]], mesh.v[nd[2]], mesh.v[nd[3]]);
    elastic += element_forces_energy(e, m_rot[ut], f, fv, e.beta_s + dt_s, out,
                                     plastic ? &m_b->plastic[ut] : nullptr);
  }
  return {inverted, turned, elastic, stiffness_volume};
}

double ImplicitIntegrator::assemble_rhs(const TetMesh& mesh, double dt_s,
                                        std::span<const Vec3> f_ext) {
  const std::int32_t n = mesh.num_nodes();
  const Vec3 g = m_config.gravity_on ? m_config.gravity_mps2 : Vec3::Zero();
  const bool has_ext = f_ext.size() == static_cast<std::size_t>(n);
  double kinetic = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : kinetic) if (n >= kParallelMin)
  for (std::int32_t i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    Vec3 b = Vec3::Zero();
    if (!node_constrained(mesh, m_el, ui)) {
      kinetic += 0.5 * m_el.node_mass[ui] * mesh.v[ui].squaredNorm();
      b = m_el.node_mass[ui] * g - m_el.node_damping[ui] * mesh.v[ui];
      if (has_ext) b += f_ext[ui];
      for (const std::int32_t ic : m_pattern.incident_of(ui))
        b += m_fe[static_cast<std::size_t>(ic)];
      b *= dt_s;
    }
    for (int c = 0; c < 3; ++c) m_rhs[3 * ui + static_cast<std::size_t>(c)] = b[c];
  }
  return kinetic;
}

// The previous step's result x, v (what this step starts from, rotations extracted by the element
// pass) against its starting energy plus the external work over it.
void ImplicitIntegrator::check_energy_balance(const ElementPass& pass, double kinetic_j,
                                              StepStatus& st) {
  st.energy_j = kinetic_j + pass.elastic_j;
  if (m_b->energy_pending) {
    st.energy_change_j = st.energy_j - m_b->energy_before - m_b->energy_work;
    // Relative to the energies involved, with a floor for a mesh (nearly) at rest, where those
    // are rounding noise: the elastic energy of a uniform strain kEnergyFloorStrain.
    const double floor_j = 0.5 * kEnergyFloorStrain * kEnergyFloorStrain * pass.stiffness_volume;
    if (!(st.energy_change_j <=
          kEnergyGainTolerance * (m_b->energy_before + st.energy_j + std::abs(m_b->energy_work)) +
              floor_j)) {
      st.energy_gain = true;
      std::fill(m_b->dv.begin(), m_b->dv.end(), 0.0);  // no warm start from an energy-injecting dv
    }
  }
  m_b->energy_pending = false;
}

// Fixed nodes stay, and so do massless nodes (left in no active tet by a cut: they belong to no
// body, and would otherwise drift forever).
double ImplicitIntegrator::apply_update(TetMesh& mesh, double dt_s, std::span<const Vec3> f_ext) {
  const std::int32_t n = mesh.num_nodes();
  const Vec3 g = m_config.gravity_on ? m_config.gravity_mps2 : Vec3::Zero();
  const bool has_ext = f_ext.size() == static_cast<std::size_t>(n);
  double work = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : work) if (n >= kParallelMin)
  for (std::int32_t i = 0; i < n; ++i) {
    const auto ui = static_cast<std::size_t>(i);
    if (mesh.fixed[ui] != 0 || !(m_el.node_mass[ui] > 0.0)) {
      mesh.v[ui].setZero();
      continue;
    }
    mesh.v[ui] += Vec3(m_b->dv[3 * ui], m_b->dv[3 * ui + 1], m_b->dv[3 * ui + 2]);
    mesh.x[ui] += dt_s * mesh.v[ui];
    Vec3 f = m_el.node_mass[ui] * g;
    if (has_ext) f += f_ext[ui];
    work += dt_s * f.dot(mesh.v[ui]);
  }
  return work;
}

void ImplicitIntegrator::update_plasticity(const TetMesh& mesh, double dt_s) {
  const auto m = static_cast<std::ptrdiff_t>(mesh.num_tets());
#pragma omp parallel for schedule(static) if (m >= kParallelMin)
  for (std::ptrdiff_t t = 0; t < m; ++t) {
    const auto ut = static_cast<std::size_t>(t);
    const TetElement& e = m_el.elements[ut];
    if (!e.active()) continue;
    const PlasticitySettings& p = m_config.plasticity_of(mesh.group[ut]);
    const double rate = std::min(dt_s * p.creep_per_s, 1.0);
    const Tet& nd = mesh.tets[ut];
    const Mat3 f = nodal_gradient(e, mesh.x[nd[0]], mesh.x[nd[1]], mesh.x[nd[2]], mesh.x[nd[3]]);
    const Mat3 g = m_rot[ut].transpose() * f;  // rotation of this step (frozen over it)
    Mat3& ep = m_b->plastic[ut];
    const Mat3 elastic = 0.5 * (g + g.transpose()) - Mat3::Identity() - ep;
    if (elastic.norm() > p.yield) ep += rate * elastic;
    const double norm = ep.norm();
    if (norm > p.max) ep *= p.max / norm;
  }
}

}  // namespace serosa::fem

namespace serosa::fem {

CsrMatrix ImplicitIntegrator::assembled_matrix() const {
  CsrMatrix a = m_a;
  const bool lagged = m_config.solver.kind == SolverKind::pcg_lagged;
  const bool blocks =
      lagged || (!m_config.solver.matrix_free && m_config.solver.kind != SolverKind::cholmod);
  if (blocks && !lagged && m_config.solver.float_matrix &&
      m_blocks_f.size() == block_storage(m_pattern))
    blocks_to_csr<float>(m_pattern, m_blocks_f, a);
  else if (blocks && m_blocks_d.size() == block_storage(m_pattern))
    blocks_to_csr<double>(m_pattern, m_blocks_d, a);
  return a;
}

}  // namespace serosa::fem
