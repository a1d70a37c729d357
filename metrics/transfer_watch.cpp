#include "metrics/transfer_watch.h"

#include <algorithm>

namespace serosa::metrics {

TransferWatch::TransferWatch(int group, Vec3 target, double radius, Vec3 up)
    : m_on(true), m_group(group), m_target(target), m_up(up.normalized()), m_radius(radius) {}

void TransferWatch::refresh_nodes(const TetMesh& mesh) {
  if (m_version == mesh.topology_version &&
      m_in_object.size() == static_cast<std::size_t>(mesh.num_nodes()))
    return;
  m_in_object.assign(static_cast<std::size_t>(mesh.num_nodes()), 0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    if (mesh.group[t] == m_group)
      for (std::int32_t v : mesh.tets[t]) m_in_object[static_cast<std::size_t>(v)] = 1;
  m_nodes.clear();
  for (std::size_t v = 0; v < m_in_object.size(); ++v)
    if (m_in_object[v] != 0) m_nodes.push_back(static_cast<std::int32_t>(v));
  m_version = mesh.topology_version;
}

void TransferWatch::find_holders(const SimState& state, std::vector<std::int64_t>& out) const {
  out.clear();
  const auto& held = state.shared.grasped;
  for (std::size_t i = 0; i < held.size(); ++i)
    if (std::any_of(held[i].begin(), held[i].end(), [&](std::int32_t v) {
          return static_cast<std::size_t>(v) < m_in_object.size() &&
                 m_in_object[static_cast<std::size_t>(v)] != 0;
        }))
      out.push_back(static_cast<std::int64_t>(i));
}

void TransferWatch::step(double time_s, const SimState& state) {
  if (!m_on) return;
  refresh_nodes(state.mesh);
  if (m_nodes.empty()) return;
  m_b->centre.setZero();
  for (std::int32_t v : m_nodes) m_b->centre += state.mesh.x[static_cast<std::size_t>(v)];
  m_b->centre /= static_cast<double>(m_nodes.size());
  find_holders(state, m_now);
  if (m_now.empty() && !m_b->holders.empty() && error_m() > m_radius) {
    ++m_b->drops;
    m_b->drop_times.push_back(time_s);
  }
  if (m_now.size() == 1) {
    // Held by one grasper: another's if it came from a hold both shared (no let-go between).
    const bool shared =
        m_b->holders.size() >= 2 &&
        std::find(m_b->holders.begin(), m_b->holders.end(), m_now[0]) != m_b->holders.end();
    if (shared && m_b->sole >= 0 && m_b->sole != m_now[0]) ++m_b->handoffs;
    m_b->sole = m_now[0];
  } else if (m_now.empty()) {
    m_b->sole = -1;
  }
  m_b->holders = m_now;
}

bool TransferWatch::placed() const {
  return m_on && m_b->holders.empty() && error_m() <= m_radius &&
         (m_b->centre - m_target).dot(m_up) <= m_radius;
}

void TransferWatch::report(nlohmann::json& metrics) const {
  if (!m_on) return;
  nlohmann::json& j = metrics["transfer"];
  j["handoffs"] = m_b->handoffs;
  j["drops"] = m_b->drops;
  j["drop_times_s"] = m_b->drop_times;
  j["placed"] = placed();
  j["placement_error_m"] = error_m();
}

}  // namespace serosa::metrics
