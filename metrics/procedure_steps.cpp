#include "metrics/procedure_steps.h"

#include <algorithm>
#include <utility>

#include "engine/node_components.h"
#include "engine/scene/scene.h"

namespace serosa::metrics {
namespace {

constexpr std::uint8_t kSpecimenNode = 1;
constexpr std::uint8_t kBaseNode = 2;

// What secures the base: an endoloop cinched round it or a stapler's line across it.
bool secures_base(const Clip& c) {
  return c.kind == Clip::Kind::kLoop || c.kind == Clip::Kind::kStaple;
}

}  // namespace

ProcedureSteps::ProcedureSteps(ProcedureGroupIds ids, std::vector<std::string> tools)
    : m_on(true), m_ids(std::move(ids)), m_tools(std::move(tools)) {
  std::sort(m_ids.mesentery.begin(), m_ids.mesentery.end());
  for (std::size_t i = 0; i < kProcedureSteps.size(); ++i) m_b->steps[i].name = kProcedureSteps[i];
}

void ProcedureSteps::step(double time_s, const SimState& state, ProcedureErrors& errors) {
  if (!m_on) return;
  m_time = time_s;
  if (!m_b->ready) init(state.mesh);
  refresh_groups(state.mesh);
  const bool cut = !state.events.cuts.empty();
  if (cut) m_pieces_stale = true;
  if (!m_b->steps[kExpose].done) expose(state);
  if (!m_b->steps[kSecure].done) secure(state);
  if (cut && !m_b->steps[kDivide].done) divide(state);
  if (cut && !m_b->steps[kTransect].done) transect(state, time_s, errors);
  if (m_b->steps[kTransect].done) follow_specimen(state, time_s, errors);
}

// Where the specimen leaves the base, its far end and its volume, from the rest state.
void ProcedureSteps::init(const TetMesh& mesh) {
  refresh_groups(mesh);
  Vec3 shared = Vec3::Zero(), base = Vec3::Zero();
  std::size_t n_shared = 0, n_base = 0;
  for (std::size_t v = 0; v < m_role.size(); ++v) {
    if ((m_role[v] & kBaseNode) == 0) continue;
    base += mesh.rest[v];
    ++n_base;
    if ((m_role[v] & kSpecimenNode) != 0) {
      shared += mesh.rest[v];
      ++n_shared;
    }
  }
  m_b->origin = n_shared > 0 ? Vec3(shared / static_cast<double>(n_shared))
                : n_base > 0 ? Vec3(base / static_cast<double>(n_base))
                             : Vec3::Zero();
  double farthest = -1.0;
  for (std::size_t v = 0; v < m_role.size(); ++v) {
    if ((m_role[v] & kSpecimenNode) == 0) continue;
    const double d = (mesh.rest[v] - m_b->origin).norm();
    if (d > farthest) {
      farthest = d;
      m_b->far = static_cast<std::int32_t>(v);
    }
  }
  m_b->volume = 0.0;
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t)
    if (mesh.group[static_cast<std::size_t>(t)] == m_ids.specimen)
      m_b->volume += mesh.rest_volume(t);
  m_b->ready = true;
}

void ProcedureSteps::refresh_groups(const TetMesh& mesh) {
  const auto n = static_cast<std::size_t>(mesh.num_nodes());
  if (m_version == mesh.topology_version && m_role.size() == n) return;
  m_role.assign(n, 0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const int g = mesh.group[t];
    const std::uint8_t bit = g == m_ids.specimen ? kSpecimenNode : g == m_ids.base ? kBaseNode : 0;
    if (bit != 0)
      for (std::int32_t v : mesh.tets[t]) m_role[static_cast<std::size_t>(v)] |= bit;
  }
  m_version = mesh.topology_version;
}

void ProcedureSteps::expose(const SimState& state) {
  const TetMesh& mesh = state.mesh;
  const auto& held = state.shared.grasped;
  for (std::size_t i = 0; i < held.size(); ++i) {
    double lift = 0.0;
    std::size_t count = 0;
    for (std::int32_t v : held[i]) {
      const auto uv = static_cast<std::size_t>(v);
      if (uv >= m_role.size() || (m_role[uv] & kSpecimenNode) == 0) continue;
      lift += (mesh.x[uv] - mesh.rest[uv]).norm();
      ++count;
    }
    if (count > 0 && lift / static_cast<double>(count) >= kExposeLift) {
      mark(kExpose, m_time, static_cast<std::int64_t>(i));
      return;
    }
  }
}

// Divided when no piece of the fold joins the base to the specimen beyond the base's zone.
void ProcedureSteps::divide(const SimState& state) {
  const TetMesh& mesh = state.mesh;
  const std::vector<std::int32_t> comp = node_components(mesh, [&](std::size_t t) {
    return std::binary_search(m_ids.mesentery.begin(), m_ids.mesentery.end(), mesh.group[t]);
  });
  std::vector<std::uint8_t> touches;  // (pieces) bit 0: a distal specimen node, bit 1: the base
  for (std::size_t v = 0; v < comp.size(); ++v) {
    if (comp[v] < 0) continue;
    const auto c = static_cast<std::size_t>(comp[v]);
    if (touches.size() <= c) touches.resize(c + 1, 0);
    if ((m_role[v] & kBaseNode) != 0) touches[c] |= 2;
    if ((m_role[v] & kSpecimenNode) != 0 && (mesh.rest[v] - m_b->origin).norm() > kBaseZone)
      touches[c] |= 1;
  }
  if (std::find(touches.begin(), touches.end(), 3) != touches.end()) return;
  mark(kDivide, m_time, static_cast<std::int64_t>(state.events.cuts.back().tool));
}

void ProcedureSteps::secure(const SimState& state) {
  for (const Clip& c : state.shared.clips) {
    if (!secures_base(c)) continue;
    if (std::find(c.groups.begin(), c.groups.end(), m_ids.specimen) == c.groups.end()) continue;
    if ((c.rest_centre_m - m_b->origin).norm() > kBaseZone) continue;
    mark(kSecure, m_time, static_cast<std::int64_t>(c.tool));
    return;
  }
}

// Transected when the specimen's far end is in a piece without the base. A loop or a staple line
// must then be on a piece with the base (the stump): else the cut went above the securing. A
// stapler's knife runs between its two lines, so its stump-side line is there.
void ProcedureSteps::transect(const SimState& state, double time_s, ProcedureErrors& errors) {
  const TetMesh& mesh = state.mesh;
  if (m_b->far < 0 || m_b->far >= mesh.num_nodes()) return;
  const std::vector<std::int32_t> comp = node_components(mesh);
  const std::int32_t far = comp[static_cast<std::size_t>(m_b->far)];
  std::vector<std::uint8_t> stump;  // (pieces) 1: holds base nodes
  for (std::size_t v = 0; v < comp.size(); ++v) {
    if (comp[v] < 0 || (m_role[v] & kBaseNode) == 0) continue;
    if (comp[v] == far) return;  // still joined
    if (stump.size() <= static_cast<std::size_t>(comp[v]))
      stump.resize(static_cast<std::size_t>(comp[v]) + 1, 0);
    stump[static_cast<std::size_t>(comp[v])] = 1;
  }
  const CutEvent& cut = state.events.cuts.back();
  mark(kTransect, time_s, static_cast<std::int64_t>(cut.tool));
  m_b->freed_at = Vec3::Zero();
  for (const Vec3& p : cut.polygon_m) m_b->freed_at += p;
  if (!cut.polygon_m.empty()) m_b->freed_at /= static_cast<double>(cut.polygon_m.size());
  double volume = 0.0;
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t) {
    const auto ut = static_cast<std::size_t>(t);
    if (mesh.group[ut] == m_ids.specimen && comp[static_cast<std::size_t>(mesh.tets[ut][0])] == far)
      volume += mesh.rest_volume(t);
  }
  m_b->fraction = m_b->volume > 0.0 ? volume / m_b->volume : 0.0;
  const bool secured =
      std::any_of(state.shared.clips.begin(), state.shared.clips.end(), [&](const Clip& c) {
        if (!secures_base(c) || c.node < 0 || c.node >= mesh.num_nodes()) return false;
        const std::int32_t k = comp[static_cast<std::size_t>(c.node)];
        return k >= 0 && static_cast<std::size_t>(k) < stump.size() &&
               stump[static_cast<std::size_t>(k)] != 0;
      });
  if (!secured)
    errors.add({ProcedureError::Kind::kTransectionAboveSecuring, time_s, m_b->freed_at});
}

// The freed specimen: extracted once carried far enough, dropped if let go before that.
void ProcedureSteps::follow_specimen(const SimState& state, double time_s,
                                     ProcedureErrors& errors) {
  const TetMesh& mesh = state.mesh;
  if (m_pieces_stale) {
    const std::vector<std::int32_t> comp = node_components(mesh);
    const std::int32_t far = m_b->far >= 0 && m_b->far < mesh.num_nodes()
                                 ? comp[static_cast<std::size_t>(m_b->far)]
                                 : -1;
    m_in_specimen.assign(comp.size(), 0);
    for (std::size_t v = 0; v < comp.size(); ++v) m_in_specimen[v] = far >= 0 && comp[v] == far;
    m_pieces_stale = false;
  }
  if (m_b->steps[kExtract].done) return;
  Vec3 centre = Vec3::Zero();
  std::size_t count = 0;
  for (std::size_t v = 0; v < m_in_specimen.size(); ++v)
    if (m_in_specimen[v] != 0) {
      centre += mesh.x[v];
      ++count;
    }
  if (count == 0) return;
  centre /= static_cast<double>(count);
  const std::int64_t tool = holder(state);
  if ((centre - m_b->freed_at).norm() >= kExtractDistance) {
    mark(kExtract, time_s, tool);
    return;
  }
  if (tool < 0 && !m_b->dropped) {
    m_b->dropped = true;
    errors.add({ProcedureError::Kind::kSpecimenDropped, time_s, centre});
  }
}

std::int64_t ProcedureSteps::holder(const SimState& state) const {
  const auto& held = state.shared.grasped;
  for (std::size_t i = 0; i < held.size(); ++i)
    for (std::int32_t v : held[i])
      if (static_cast<std::size_t>(v) < m_in_specimen.size() &&
          m_in_specimen[static_cast<std::size_t>(v)] != 0)
        return static_cast<std::int64_t>(i);
  return -1;
}

void ProcedureSteps::mark(Index i, double time_s, std::int64_t tool) {
  m_b->steps[i].done = true;
  m_b->steps[i].time_s = time_s;
  m_b->steps[i].tool = tool;
}

bool ProcedureSteps::completed() const {
  return std::all_of(m_b->steps.begin(), m_b->steps.end(),
                     [](const ProcedureStep& s) { return s.done; });
}

void ProcedureSteps::report(nlohmann::json& metrics) const {
  if (!m_on) return;
  nlohmann::json steps = nlohmann::json::array();
  for (const ProcedureStep& s : m_b->steps) {
    nlohmann::json j{{"name", s.name}, {"done", s.done}};
    j["time_s"] = s.done ? nlohmann::json(s.time_s) : nlohmann::json(nullptr);
    j["tool"] = s.tool >= 0 && static_cast<std::size_t>(s.tool) < m_tools.size()
                    ? nlohmann::json(m_tools[static_cast<std::size_t>(s.tool)])
                    : nlohmann::json(nullptr);
    steps.push_back(std::move(j));
  }
  metrics["procedure"] = {{"steps", std::move(steps)},
                          {"completed", completed()},
                          {"specimen_volume_fraction", m_b->fraction}};
}

void ProcedureSteps::adopt() {
  for (std::size_t i = 0; i < m_b->steps.size(); ++i) m_b->steps[i].name = kProcedureSteps[i];
  m_version = ~0ull;
  m_pieces_stale = true;
}

}  // namespace serosa::metrics
