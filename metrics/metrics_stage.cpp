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
  m_b->path.assign(k, 0.0);
  m_b->last_tip.assign(k, Vec3::Zero());
  m_b->last_in_port.assign(k, 0);
  m_b->force_max.assign(k, 0.0);
  m_b->force_sum.assign(k, 0.0);
  m_b->force_steps.assign(k, 0);
  m_moved.assign(k, 0.0);
  m_window = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::lround(kIdleWindowS / scene.settings.dt_s)));
  m_load.assign(k, 0.0);
  m_b->out_of_view_s.assign(k, 0.0);
  m_tear_stress = scene.metrics.tear_stress_pa;
  m_targets = scene.metrics.view_targets_m;
  m_b->target_first_s.assign(m_targets.size(), -1.0);
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

void MetricsStage::bind(MetricsBlock& b) {
  if (!b.begun) {  // the first step: the zero sums, shaped for the scene
    b = m_b.unbound();
    b.exchanges = m_exchanges.unbound_block();
    b.errors = m_errors.unbound_block();
    b.steps = m_steps.unbound_block();
    b.splits = m_splits.unbound_block();
    b.clips = m_clips.unbound_block();
    b.transfer = m_transfer.unbound_block();
    b.begun = true;
  }
  m_b.bind(b);
  m_exchanges.bind(b.exchanges);
  m_errors.bind(b.errors);
  m_steps.bind(b.steps);
  m_splits.bind(b.splits);
  m_clips.bind(b.clips);
  m_transfer.bind(b.transfer);
}

void MetricsStage::adopt(SimState& state) {
  const MetricsBlock& b = state.blocks.metrics;
  if (!b.begun && state.step > 0)
    throw BlockMismatch("no sums, though the state has taken " + std::to_string(state.step) +
                        " steps");
  if (b.begun) {
    const std::size_t tools = m_names.size();
    for (std::size_t size :
         {b.path.size(), b.last_tip.size(), b.force_max.size(), b.force_sum.size(),
          b.force_steps.size(), b.out_of_view_s.size(), b.last_in_port.size()})
      if (size != tools)
        throw BlockMismatch("sums of " + std::to_string(size) + " tools, the scene has " +
                            std::to_string(tools));
    if (b.target_first_s.size() != m_targets.size())
      throw BlockMismatch("another number of view targets than the scene's");
    if (!b.recent.empty() && b.recent.size() != m_window * tools)
      throw BlockMismatch("another idle window than the scene's");
    for (const StepSplit& s : b.splits.done)
      if (s.path_m.size() != tools) throw BlockMismatch("a step's split of another tool count");
    for (const ProcedureError& e : b.errors.errors)
      if (e.kind > ProcedureError::Kind::kSpecimenDropped)
        throw BlockMismatch("an unknown kind of procedure error");
  }
  bind(state.blocks.metrics);  // (shapes a block restored from before the first step)
  m_rest_valid = false;
  m_errors.adopt();
  m_steps.adopt();
  m_transfer.adopt();
  state.shared.bleeds.clear();
  publish_bleeds(state);
}

void MetricsStage::step(const StepContext& ctx, SimState& state) {
  bind(state.blocks.metrics);
  m_b->time = ctx.time_s + ctx.dt_s;
  const std::size_t k = std::min(m_names.size(), state.tools.size());
  m_exchanges.step(m_b->time, ctx.dt_s, state.tools);
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3 tip(state.tools[i].tip_m[0], state.tools[i].tip_m[1], state.tools[i].tip_m[2]);
    // Into or out of its port an exchange moves an instrument at once: no hand's travel.
    const bool port = in_port(state.tools[i]) != m_b->last_in_port[i];
    m_b->last_in_port[i] = in_port(state.tools[i]);
    m_moved[i] = m_b->have_last && !port ? (tip - m_b->last_tip[i]).norm() : 0.0;
    m_b->path[i] += m_moved[i];
    m_b->last_tip[i] = tip;
  }
  const auto& f = state.events.tool_force_n;
  const auto& reactions = state.events.tool_reactions;
  for (std::size_t i = 0; i < k; ++i)  // a scissors' blades load the tissue with no net force
    m_load[i] = (i < f.size() ? f[i].norm() : 0.0) +
                (i < reactions.size() ? reactions[i].blade_force_n : 0.0);
  // (The first step's time counts towards the first split, though no move can be measured in it.)
  m_splits.add(m_moved, m_b->have_last && add_use(m_moved, m_load, ctx.dt_s), ctx.dt_s);
  m_b->have_last = true;
  if (!f.empty()) {
    m_b->forces = true;
    for (std::size_t i = 0; i < k; ++i) {
      const double mag = m_load[i];
      if (!(mag > 0.0)) continue;
      m_b->force_max[i] = std::max(m_b->force_max[i], mag);
      m_b->force_sum[i] += mag;
      ++m_b->force_steps[i];
    }
  }
  add_view(state.tools, ctx.dt_s);
  for (const CutEvent& cut : state.events.cuts) add_cut(cut);
  if (m_errors.active()) m_errors.step(m_b->time, state);
  m_clips.step(state.shared.clips);
  m_transfer.step(m_b->time, state);
  follow_steps(state);
  if (static_cast<std::int64_t>(ctx.step) % m_stress_every == 0)
    add_stress(peak_stress(state.mesh));
}

void MetricsStage::follow_steps(SimState& state) {
  std::array<bool, kProcedureSteps.size()> before{};
  for (std::size_t i = 0; i < before.size(); ++i) before[i] = m_steps.steps()[i].done;
  m_steps.step(m_b->time, state, m_errors);
  for (std::size_t i = 0; i < before.size(); ++i)
    if (!before[i] && m_steps.steps()[i].done) m_splits.close(i);
  publish_bleeds(state);
}

bool MetricsStage::add_use(const std::vector<double>& moved, const std::vector<double>& load,
                           double dt_s) {
  const std::size_t n = moved.size();
  const std::size_t slot = static_cast<std::size_t>(m_b->recent_at++ % m_window);
  m_b->recent.resize(m_window * n, 0.0);
  std::copy(moved.begin(), moved.end(),
            m_b->recent.begin() + static_cast<std::ptrdiff_t>(slot * n));
  // Early on the window holds only the steps taken so far.
  const auto filled = static_cast<std::size_t>(std::min<std::uint64_t>(m_b->recent_at, m_window));
  bool any_moving = false, all_at_work = true, over = false;
  std::size_t hands = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double f = i < load.size() ? load[i] : 0.0;
    over = over || f > m_force_limit;
    if (!at_hand(i)) continue;
    ++hands;
    double path = 0.0;
    for (std::size_t k = 0; k < m_window; ++k) path += m_b->recent[k * n + i];
    const bool moving = path > kIdleSpeed * static_cast<double>(filled) * dt_s;
    any_moving = any_moving || moving;
    all_at_work = all_at_work && (moving || f > 0.0);
  }
  if (any_moving) {
    m_b->active_s += dt_s;
    if (hands >= 2 && all_at_work) m_b->bimanual_s += dt_s;
  } else {
    m_b->idle_s += dt_s;
  }
  if (over) m_b->force_over_s += dt_s;
  return !any_moving;
}

// With hands (the inputs name them) the instruments the two hands hold now; else every
// instrument but the endoscope.
bool MetricsStage::at_hand(std::size_t tool) const {
  if (!m_exchanges.hands_seen()) return m_hand[tool] != 0;
  return m_exchanges.held(0) == tool || m_exchanges.held(1) == tool;
}

void MetricsStage::add_stress(double now_pa) {
  m_b->peak_stress = std::max(m_b->peak_stress, now_pa);
  if (!m_tear_stress) return;
  const bool over = now_pa > *m_tear_stress;
  if (over && !m_b->over_tear) m_b->tear_times.push_back(m_b->time);
  m_b->over_tear = over;
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
    if (m_b->target_first_s[k] < 0.0 && n > 0.0 && n <= kTargetRange && d.dot(view.dir) >= n * cone)
      m_b->target_first_s[k] = m_b->time;
  }
  for (std::size_t i = 0; i < tools.size() && i < m_hand.size(); ++i) {
    const ToolState& t = tools[i];
    if (m_hand[i] == 0 || !scope_posed(t) || in_port(t)) continue;  // not in the body
    if (!in_view(view, Vec3(t.tip_m[0], t.tip_m[1], t.tip_m[2]))) m_b->out_of_view_s[i] += dt_s;
  }
}

std::size_t MetricsStage::targets_missed() const {
  return static_cast<std::size_t>(std::count_if(
      m_b->target_first_s.begin(), m_b->target_first_s.end(), [](double t) { return t < 0.0; }));
}

double MetricsStage::targets_time_s() const {
  if (targets_missed() > 0 || m_b->target_first_s.empty()) return m_b->time;
  return *std::max_element(m_b->target_first_s.begin(), m_b->target_first_s.end());
}

void MetricsStage::add_cut(const CutEvent& cut) {
  for (std::size_t i = 0; i < cut.removed_volumes_m3.size(); ++i) {
    const double v = cut.removed_volumes_m3[i];
    m_b->cut_volume += v;
    ++m_b->cut_tets;
    if (m_planned.empty()) continue;
    const double d = distance_to_polyline(cut.removed_centroids_m[i], m_planned);
    m_b->dev_weighted += v * d;
    m_b->dev_max = std::max(m_b->dev_max, d);
    if (d > m_band) m_b->collateral += v;
  }
}

nlohmann::json MetricsStage::report() const {
  nlohmann::json j;
  j["time_s"] = m_b->time;
  for (std::size_t i = 0; i < m_names.size(); ++i) {
    j["path_length_m"][m_names[i]] = m_b->path[i];
    if (m_b->forces) {
      j["force_max_n"][m_names[i]] = m_b->force_max[i];
      j["force_mean_n"][m_names[i]] =
          m_b->force_steps[i] > 0 ? m_b->force_sum[i] / static_cast<double>(m_b->force_steps[i])
                                  : 0.0;
    }
  }
  if (m_scope)
    for (std::size_t i = 0; i < m_names.size(); ++i)
      if (m_hand[i] != 0) j["out_of_view_s"][m_names[i]] = m_b->out_of_view_s[i];
  if (!m_targets.empty()) {
    j["view_targets"]["centred"] = m_targets.size() - targets_missed();
    j["view_targets"]["missed"] = targets_missed();
    j["view_targets"]["time_s"] = targets_time_s();
  }
  j["peak_stress_pa"] = m_b->peak_stress;
  if (m_tear_stress) {
    j["tears"] = tears();
    j["tear_times_s"] = m_b->tear_times;
  }
  j["idle_time_s"] = m_b->idle_s;
  j["bimanual_fraction"] = bimanual_fraction();
  if (m_b->forces) j["force_over_s"] = m_b->force_over_s;
  j["cut"]["tets"] = m_b->cut_tets;
  j["cut"]["volume_m3"] = m_b->cut_volume;
  if (!m_planned.empty()) {
    j["cut"]["deviation_mean_m"] = deviation_mean_m();
    j["cut"]["deviation_max_m"] = m_b->dev_max;
    j["cut"]["collateral_m3"] = m_b->collateral;
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
