#include "metrics/procedure_errors.h"

#include <algorithm>

#include "engine/hook.h"

namespace serosa::metrics {

ProcedureErrors::ProcedureErrors(std::optional<int> artery, std::vector<int> protected_groups)
    : m_artery(artery), m_protected(std::move(protected_groups)) {
  std::sort(m_protected.begin(), m_protected.end());
}

void ProcedureErrors::step(double time_s, const SimState& state) {
  if (m_artery) check_cuts(time_s, state);
  if (!m_protected.empty()) check_burns(time_s, state);
}

// A cut that removed one of the artery's tets went through it (whatever the method: removal adds
// none).
void ProcedureErrors::check_cuts(double time_s, const SimState& state) {
  const bool secured =
      std::any_of(state.shared.clips.begin(), state.shared.clips.end(), [&](const Clip& c) {
        return std::find(c.groups.begin(), c.groups.end(), *m_artery) != c.groups.end();
      });
  for (const CutEvent& cut : state.events.cuts) {
    const auto& g = cut.removed_groups;
    if (secured || std::find(g.begin(), g.end(), *m_artery) == g.end()) continue;
    Vec3 where = Vec3::Zero();
    for (const Vec3& c : cut.removed_centroids_m) where += c;
    if (!cut.removed_centroids_m.empty())
      where /= static_cast<double>(cut.removed_centroids_m.size());
    m_b->errors.push_back({ProcedureError::Kind::kBleeding, time_s, where});
  }
}

void ProcedureErrors::check_burns(double time_s, const SimState& state) {
  const TetMesh& mesh = state.mesh;
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  if (m_prot_version != mesh.topology_version || m_node_prot.size() != n) {
    m_node_prot.assign(n, 0);
    for (std::size_t t = 0; t < mesh.tets.size(); ++t)
      if (std::binary_search(m_protected.begin(), m_protected.end(), mesh.group[t]))
        for (std::int32_t v : mesh.tets[t]) m_node_prot[static_cast<std::size_t>(v)] = 1;
    m_prot_version = mesh.topology_version;
  }
  // One injury per press of the pedal, however long the hook stays on the wall.
  const bool pedal = std::any_of(state.tools.begin(), state.tools.end(),
                                 [](const ToolState& t) { return pedal_down(t); });
  if (!pedal) m_b->counted = false;
  const std::vector<std::uint8_t>& coag = state.blocks.cutting.coagulated;
  if (state.blocks.cutting.coagulated_version == m_b->seen_coag) return;
  m_b->seen_coag = state.blocks.cutting.coagulated_version;
  m_b->burnt.resize(n, 0);
  std::optional<Vec3> first;
  for (std::size_t v = 0; v < n && v < coag.size(); ++v) {
    if (coag[v] == 0 || m_node_prot[v] == 0 || m_b->burnt[v] != 0) continue;
    m_b->burnt[v] = 1;
    if (!first) first = mesh.x[v];
  }
  // Marks that appear with the pedal up are the wound of a press already counted (its cut's
  // nodes, their clones), not a burn of their own.
  if (first && pedal && !m_b->counted) {
    m_b->errors.push_back({ProcedureError::Kind::kThermalInjury, time_s, *first});
    m_b->counted = true;
  }
}

std::int64_t ProcedureErrors::count(ProcedureError::Kind kind) const {
  return std::count_if(m_b->errors.begin(), m_b->errors.end(),
                       [&](const ProcedureError& e) { return e.kind == kind; });
}

const char* ProcedureErrors::kind_name(ProcedureError::Kind kind) {
  switch (kind) {
    case ProcedureError::Kind::kBleeding:
      return "bleeding";
    case ProcedureError::Kind::kThermalInjury:
      return "thermal_injury";
    case ProcedureError::Kind::kTransectionAboveSecuring:
      return "transection_above_securing";
    case ProcedureError::Kind::kSpecimenDropped:
      return "specimen_dropped";
  }
  return "?";
}

void ProcedureErrors::report(nlohmann::json& metrics, bool steps) const {
  if (!active()) return;
  metrics["bleeding_events"] = count(ProcedureError::Kind::kBleeding);
  metrics["thermal_injuries"] = count(ProcedureError::Kind::kThermalInjury);
  if (steps) {
    metrics["transections_above_securing"] = count(ProcedureError::Kind::kTransectionAboveSecuring);
    metrics["specimens_dropped"] = count(ProcedureError::Kind::kSpecimenDropped);
  }
  nlohmann::json list = nlohmann::json::array();
  for (const ProcedureError& e : m_b->errors)
    list.push_back({{"kind", kind_name(e.kind)},
                    {"time_s", e.time_s},
                    {"where_m", {e.where_m.x(), e.where_m.y(), e.where_m.z()}}});
  metrics["errors"] = std::move(list);
}

}  // namespace serosa::metrics
