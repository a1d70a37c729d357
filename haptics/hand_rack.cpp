#include "haptics/hand_rack.h"

namespace serosa::haptics {
namespace {

Vec3 vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }
std::array<double, 3> arr(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

ToolState TrocarMap::pose(const ToolState& s) const {
  ToolState out = s;
  out.tip_m = arr(point(vec(s.tip_m)));
  const Quat q = (rotation * Quat(s.quat_wxyz[0], s.quat_wxyz[1], s.quat_wxyz[2], s.quat_wxyz[3]))
                     .normalized();
  out.quat_wxyz = {q.w(), q.x(), q.y(), q.z()};
  return out;
}

TrocarMap TrocarMap::inverse() const { return {rotation.conjugate(), to_m, from_m}; }

TrocarMap trocar_map(const Trocar& from, const Trocar& to) {
  return {(to.rotation * from.rotation.conjugate()).normalized(), from.pivot_m, to.pivot_m};
}

HandRack::HandRack(std::vector<RackInstrument> instruments,
                   std::array<std::optional<std::size_t>, kHandles> held)
    : m_items(std::move(instruments)), m_held(held) {
  for (std::size_t h = 0; h < kHandles; ++h)
    if (m_held[h]) m_handle[h] = m_items[*m_held[h]].trocar;
}

std::optional<std::size_t> HandRack::exchange(std::size_t h) {
  if (!m_held[h] || m_items.empty()) return std::nullopt;
  const std::size_t n = m_items.size();
  for (std::size_t k = 1; k < n; ++k) {
    const std::size_t next = (*m_held[h] + k) % n;
    bool taken = false;
    for (std::size_t o = 0; o < kHandles; ++o) taken = taken || (o != h && m_held[o] == next);
    if (taken) continue;
    m_held[h] = next;
    m_entering[h] = true;
    return next;
  }
  return std::nullopt;
}

void HandRack::follow(std::size_t h, const ToolState& handle_pose) {
  if (!m_entering[h]) return;
  // The insertion: the tip's distance from the pivot, along the shaft.
  if ((vec(handle_pose.tip_m) - m_handle[h].pivot_m).norm() <= kEntryDepthM) m_entering[h] = false;
}

ToolState HandRack::to_instrument(std::size_t h, const ToolState& handle_pose) const {
  if (!m_held[h]) return handle_pose;
  return trocar_map(m_handle[h], m_items[*m_held[h]].trocar).pose(handle_pose);
}

ToolContact HandRack::to_handle(std::size_t h, const ToolContact& c) const {
  if (!m_held[h]) return c;
  const TrocarMap back = trocar_map(m_items[*m_held[h]].trocar, m_handle[h]);
  ToolContact out = c;
  out.sim_tip_m = arr(back.point(vec(c.sim_tip_m)));
  for (std::uint32_t k = 0; k < c.n_contacts && k < out.contacts.size(); ++k) {
    out.contacts[k].point_m = arr(back.point(vec(c.contacts[k].point_m)));
    out.contacts[k].normal = arr(back.direction(vec(c.contacts[k].normal)));
  }
  out.held_pull_N = arr(back.direction(vec(c.held_pull_N)));
  out.shaft_push_N = arr(back.direction(vec(c.shaft_push_N)));
  return out;
}

}  // namespace serosa::haptics
