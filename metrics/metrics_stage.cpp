#include "metrics/metrics_stage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/board_normal.h"
#include "engine/instrument_hold.h"
#include "engine/scope_view.h"
#include "engine/sim_state.h"
#include "engine/state_codec.h"
#include "engine/tool_geometry.h"

namespace serosa::metrics {

double distance_to_polyline(const Vec3& p, const std::vector<Vec3>& line) {
  if (line.empty()) return 0.0;
  if (line.size() == 1) return (p - line[0]).norm();
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    d = std::min(d, distance_to_segment(p, line[i], line[i + 1]));
  return d;
}

namespace {

std::optional<int> id_of(const std::map<int, std::string>& names, const std::string& name) {
  for (const auto& [id, n] : names)
    if (n == name) return id;
  return std::nullopt;
}

ProcedureErrors watch(const MetricsSettings& m, const std::map<int, std::string>& names) {
  std::optional<int> artery;
  if (m.artery) artery = id_of(names, *m.artery);
  std::vector<int> prot;
  for (const std::string& g : m.protected_groups)
    if (const auto id = id_of(names, g)) prot.push_back(*id);
  return {artery, prot};
}

ProcedureSteps follow(const MetricsSettings& m, const std::map<int, std::string>& names,
                      const std::vector<std::string>& tools) {
  if (!m.procedure) return {};
  ProcedureGroupIds ids;
  ids.specimen = id_of(names, m.procedure->specimen).value_or(-1);
  ids.base = id_of(names, m.procedure->base).value_or(-1);
  if (const auto g = id_of(names, m.procedure->mesentery)) ids.mesentery.push_back(*g);
  if (m.artery)
    if (const auto g = id_of(names, *m.artery)) ids.mesentery.push_back(*g);
  return {ids, tools};
}

}  // namespace

MetricsStage::MetricsStage(const Scene& scene, LameTable lame, std::int64_t stress_every,
                           const std::map<int, std::string>& group_names)
    : m_force_limit(scene.metrics.force_limit_n),
      m_planned(scene.metrics.planned_cut_m),
      m_band(scene.metrics.cut_band_m),
      m_lame(std::move(lame)),
      m_stress_every(std::max<std::int64_t>(stress_every, 1)) {
  for (const Tool& t : scene.tools) {
    if (t.kind == ToolKind::kEndoscope && !m_scope) m_scope = m_names.size();
    m_names.push_back(t.name);
    m_hand.push_back(t.kind != ToolKind::kEndoscope ? 1 : 0);
  }
  const std::size_t k = m_names.size();
  m_path.assign(k, 0.0);
  m_last_tip.assign(k, Vec3::Zero());
  m_last_in_port.assign(k, 0);
  m_force_max.assign(k, 0.0);
  m_force_sum.assign(k, 0.0);
  m_force_steps.assign(k, 0);
  m_moved.assign(k, 0.0);
  m_window = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::lround(kIdleWindowS / scene.settings.dt_s)));
  m_load.assign(k, 0.0);
  m_out_of_view_s.assign(k, 0.0);
  m_tear_stress = scene.metrics.tear_stress_pa;
  m_targets = scene.metrics.view_targets_m;
  m_target_first_s.assign(m_targets.size(), -1.0);
  m_errors = watch(scene.metrics, group_names);
  m_steps = follow(scene.metrics, group_names, m_names);
  if (m_errors.active() && scene.metrics.artery && scene.settings.has(Effect::kClips))
    if (const auto artery = id_of(group_names, *scene.metrics.artery))
      m_clips = ClipPlacement(*artery, scene.metrics.clip_target_m);
  if (const auto& t = scene.metrics.transfer)
    if (const auto object = id_of(group_names, t->object))
      m_transfer = TransferWatch(*object, t->target_m, t->radius_m, board_normal(scene));
  if (m_steps.active()) m_splits = StepSplits(m_steps.steps().size(), m_names, m_hand);
}

void MetricsStage::step(const StepContext& ctx, SimState& state) {
  m_time = ctx.time_s + ctx.dt_s;
  const std::size_t k = std::min(m_names.size(), state.tools.size());
  m_exchanges.step(m_time, ctx.dt_s, state.tools);
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3 tip(state.tools[i].tip_m[0], state.tools[i].tip_m[1], state.tools[i].tip_m[2]);
    // Into or out of its port an exchange moves an instrument at once: no hand's travel.
    const bool port = in_port(state.tools[i]) != m_last_in_port[i];
    m_last_in_port[i] = in_port(state.tools[i]);
    m_moved[i] = m_have_last && !port ? (tip - m_last_tip[i]).norm() : 0.0;
    m_path[i] += m_moved[i];
    m_last_tip[i] = tip;
  }
  const auto& f = state.events.tool_force_n;
  const auto& reactions = state.events.tool_reactions;
  for (std::size_t i = 0; i < k; ++i)  // a scissors' blades load the tissue with no net force
    m_load[i] = (i < f.size() ? f[i].norm() : 0.0) +
                (i < reactions.size() ? reactions[i].blade_force_n : 0.0);
  // (The first step's time counts towards the first split, though no move can be measured in it.)
  m_splits.add(m_moved, m_have_last && add_use(m_moved, m_load, ctx.dt_s), ctx.dt_s);
  m_have_last = true;
  if (!f.empty()) {
    m_forces = true;
    for (std::size_t i = 0; i < k; ++i) {
      const double mag = m_load[i];
      if (!(mag > 0.0)) continue;
      m_force_max[i] = std::max(m_force_max[i], mag);
      m_force_sum[i] += mag;
      ++m_force_steps[i];
    }
  }
  add_view(state.tools, ctx.dt_s);
  for (const CutEvent& cut : state.events.cuts) add_cut(cut);
  if (m_errors.active()) m_errors.step(m_time, state);
  m_clips.step(state.shared.clips);
  m_transfer.step(m_time, state);
  follow_steps(state);
  if (static_cast<std::int64_t>(ctx.step) % m_stress_every == 0)
    add_stress(peak_stress(state.mesh));
}

void MetricsStage::follow_steps(SimState& state) {
  std::array<bool, kProcedureSteps.size()> before{};
  for (std::size_t i = 0; i < before.size(); ++i) before[i] = m_steps.steps()[i].done;
  m_steps.step(m_time, state, m_errors);
  for (std::size_t i = 0; i < before.size(); ++i)
    if (!before[i] && m_steps.steps()[i].done) m_splits.close(i);
  publish_bleeds(state);
}

bool MetricsStage::add_use(const std::vector<double>& moved, const std::vector<double>& load,
                           double dt_s) {
  const std::size_t n = moved.size();
  const std::size_t slot = static_cast<std::size_t>(m_recent_at++ % m_window);
  m_recent.resize(m_window * n, 0.0);
  std::copy(moved.begin(), moved.end(), m_recent.begin() + static_cast<std::ptrdiff_t>(slot * n));
  // Early on the window holds only the steps taken so far.
  const auto filled = static_cast<std::size_t>(std::min<std::uint64_t>(m_recent_at, m_window));
  bool any_moving = false, all_at_work = true, over = false;
  std::size_t hands = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = i < load.size() ? load[i] : 0.0;
    over = over || f > m_force_limit;
    if (!at_hand(i)) continue;
    ++hands;
    double path = 0.0;
    for (std::size_t k = 0; k < m_window; ++k) path += m_recent[k * n + i];
    const bool moving = path > kIdleSpeed * static_cast<double>(filled) * dt_s;
    any_moving = any_moving || moving;
    all_at_work = all_at_work && (moving || f > 0.0);
  }
  if (any_moving) {
    m_active_s += dt_s;
    if (hands >= 2 && all_at_work) m_bimanual_s += dt_s;
  } else {
    m_idle_s += dt_s;
  }
  if (over) m_force_over_s += dt_s;
  return !any_moving;
}

// With hands (the inputs name them) the instruments the two hands hold now; else every
// instrument but the endoscope.
bool MetricsStage::at_hand(std::size_t tool) const {
  if (!m_exchanges.hands_seen()) return m_hand[tool] != 0;
  return m_exchanges.held(0) == tool || m_exchanges.held(1) == tool;
}

void MetricsStage::add_stress(double now_pa) {
  m_peak_stress = std::max(m_peak_stress, now_pa);
  if (!m_tear_stress) return;
  const bool over = now_pa > *m_tear_stress;
  if (over && !m_over_tear) m_tear_times.push_back(m_time);
  m_over_tear = over;
}

double MetricsStage::peak_stress(const TetMesh& mesh) {
  if (!m_rest_valid || m_rest_version != mesh.topology_version ||
      m_rest.ok.size() != static_cast<std::size_t>(mesh.num_tets())) {
    fill_rest_stress(mesh, m_lame, m_rest);
    m_rest_version = mesh.topology_version;
    m_rest_valid = true;
  }
  return peak_von_mises_pa(mesh, m_rest);
}

void MetricsStage::add_view(const std::vector<ToolState>& tools, double dt_s) {
  if (!m_scope || *m_scope >= tools.size() || !scope_posed(tools[*m_scope])) return;
  const ScopeView view = scope_view(tools[*m_scope]);
  const double cone = std::cos(kTargetConeDeg * std::numbers::pi / 180.0);
  for (std::size_t k = 0; k < m_targets.size(); ++k) {
    const Vec3 d = m_targets[k] - view.eye;
    const double n = d.norm();
    if (m_target_first_s[k] < 0.0 && n > 0.0 && n <= kTargetRange && d.dot(view.dir) >= n * cone)
      m_target_first_s[k] = m_time;
  }
  for (std::size_t i = 0; i < tools.size() && i < m_hand.size(); ++i) {
    const ToolState& t = tools[i];
    if (m_hand[i] == 0 || !scope_posed(t) || in_port(t)) continue;  // not in the body
    if (!in_view(view, Vec3(t.tip_m[0], t.tip_m[1], t.tip_m[2]))) m_out_of_view_s[i] += dt_s;
  }
}

std::size_t MetricsStage::targets_missed() const {
  return static_cast<std::size_t>(std::count_if(m_target_first_s.begin(), m_target_first_s.end(),
                                                [](double t) { return t < 0.0; }));
}

double MetricsStage::targets_time_s() const {
  if (targets_missed() > 0 || m_target_first_s.empty()) return m_time;
  return *std::max_element(m_target_first_s.begin(), m_target_first_s.end());
}

void MetricsStage::add_cut(const CutEvent& cut) {
  for (std::size_t i = 0; i < cut.removed_volumes_m3.size(); ++i) {
    const double v = cut.removed_volumes_m3[i];
    m_cut_volume += v;
    ++m_cut_tets;
    if (m_planned.empty()) continue;
    const double d = distance_to_polyline(cut.removed_centroids_m[i], m_planned);
    m_dev_weighted += v * d;
    m_dev_max = std::max(m_dev_max, d);
    if (d > m_band) m_collateral += v;
  }
}

nlohmann::json MetricsStage::report() const {
  nlohmann::json j;
  j["time_s"] = m_time;
  for (std::size_t i = 0; i < m_names.size(); ++i) {
    j["path_length_m"][m_names[i]] = m_path[i];
    if (m_forces) {
      j["force_max_n"][m_names[i]] = m_force_max[i];
      j["force_mean_n"][m_names[i]] =
          m_force_steps[i] > 0 ? m_force_sum[i] / static_cast<double>(m_force_steps[i]) : 0.0;
    }
  }
  if (m_scope)
    for (std::size_t i = 0; i < m_names.size(); ++i)
      if (m_hand[i] != 0) j["out_of_view_s"][m_names[i]] = m_out_of_view_s[i];
  if (!m_targets.empty()) {
    j["view_targets"]["centred"] = m_targets.size() - targets_missed();
    j["view_targets"]["missed"] = targets_missed();
    j["view_targets"]["time_s"] = targets_time_s();
  }
  j["peak_stress_pa"] = m_peak_stress;
  if (m_tear_stress) {
    j["tears"] = tears();
    j["tear_times_s"] = m_tear_times;
  }
  j["idle_time_s"] = m_idle_s;
  j["bimanual_fraction"] = bimanual_fraction();
  if (m_forces) j["force_over_s"] = m_force_over_s;
  j["cut"]["tets"] = m_cut_tets;
  j["cut"]["volume_m3"] = m_cut_volume;
  if (!m_planned.empty()) {
    j["cut"]["deviation_mean_m"] = deviation_mean_m();
    j["cut"]["deviation_max_m"] = m_dev_max;
    j["cut"]["collateral_m3"] = m_collateral;
    j["cut"]["band_m"] = m_band;
  }
  m_exchanges.report(j, m_names);
  m_errors.report(j, m_steps.active());
  m_steps.report(j);
  m_splits.report(j);
  m_clips.report(j);
  m_transfer.report(j);
  return j;
}

void MetricsStage::save(StateWriter& out) const {
  out.u8(m_forces ? 1 : 0);
  out.f64(m_time);
  out.array(m_path);
  out.array(m_last_tip);
  out.u8(m_have_last ? 1 : 0);
  out.array(m_force_max);
  out.array(m_force_sum);
  out.array(m_force_steps);
  out.array(m_out_of_view_s);
  out.array(m_target_first_s);
  out.array(m_recent);
  out.u64(m_recent_at);
  for (double v : {m_peak_stress, m_cut_volume, m_collateral, m_dev_weighted, m_dev_max, m_idle_s,
                   m_active_s, m_bimanual_s, m_force_over_s})
    out.f64(v);
  out.u64(static_cast<std::uint64_t>(m_cut_tets));
  out.u8(m_over_tear ? 1 : 0);
  out.array(m_tear_times);
  out.array(m_last_in_port);
  m_exchanges.save(out);
  m_errors.save(out);  // (nothing when no errors are watched for)
  m_steps.save(out);   // (nothing when no procedure is followed)
  m_splits.save(out);  // (likewise)
  m_clips.save(out);   // (nothing without clips on an artery)
  m_transfer.save(out);
}

void MetricsStage::restore(StateReader& in, SimState& state) {
  m_rest_valid = false;
  const std::size_t tools = m_path.size();
  m_forces = in.u8() != 0;
  m_time = in.f64();
  in.array(m_path);
  in.array(m_last_tip);
  m_have_last = in.u8() != 0;
  in.array(m_force_max);
  in.array(m_force_sum);
  in.array(m_force_steps);
  in.array(m_out_of_view_s);
  in.array(m_target_first_s);
  if (m_target_first_s.size() != m_targets.size()) in.fail("another number of view targets");
  in.array(m_recent);
  m_recent_at = in.u64();
  if (!m_recent.empty() && m_recent.size() != m_window * tools)
    in.fail("another idle window than the scene's");
  if (m_path.size() != tools || m_last_tip.size() != tools || m_force_max.size() != tools ||
      m_force_sum.size() != tools || m_force_steps.size() != tools ||
      m_out_of_view_s.size() != tools)
    in.fail("another number of tools than the scene's");
  for (double* v : {&m_peak_stress, &m_cut_volume, &m_collateral, &m_dev_weighted, &m_dev_max,
                    &m_idle_s, &m_active_s, &m_bimanual_s, &m_force_over_s})
    *v = in.f64();
  m_cut_tets = static_cast<std::int64_t>(in.u64());
  m_over_tear = in.u8() != 0;
  in.array(m_tear_times);
  in.array(m_last_in_port);
  if (m_last_in_port.size() != tools) in.fail("another number of tools than the scene's");
  m_exchanges.restore(in);
  m_errors.restore(in);
  m_steps.restore(in);
  m_splits.restore(in);
  m_clips.restore(in);
  m_transfer.restore(in);
  state.shared.bleeds.clear();
  publish_bleeds(state);
}

// The bleeding the view shows: appended when one begins (the list only grows).
void MetricsStage::publish_bleeds(SimState& state) const {
  const std::int64_t k = m_errors.count(ProcedureError::Kind::kBleeding);
  if (static_cast<std::int64_t>(state.shared.bleeds.size()) == k) return;
  state.shared.bleeds.clear();
  for (const ProcedureError& e : m_errors.errors())
    if (e.kind == ProcedureError::Kind::kBleeding)
      state.shared.bleeds.emplace_back(e.where_m, e.time_s);
}

}  // namespace serosa::metrics
