#include "haptics/mouse_device.h"

#include <algorithm>
#include <cmath>

#include "engine/instrument_hold.h"

namespace serosa::haptics {

JointState reach(const Trocar& t, const Vec3& goal_tip_m, const JointState& previous,
                 const MouseMapping& m) {
  Vec3 local = t.rotation.conjugate() * (goal_tip_m - t.pivot_m);
  const double n = local.norm();
  if (!(n > 1e-9)) {  // at the pivot (or not finite): keep the direction, shortest insertion
    JointState q = previous;
    q.insertion_m = m.min_insertion_m;
    return q;
  }
  Vec3 d = local / n;
  // Outside the cone the port allows: the nearest direction on its rim.
  const double cos_max = std::cos(m.max_cone_rad);
  if (d.z() < cos_max) {
    Vec3 across(d.x(), d.y(), 0.0);
    if (across.norm() < 1e-12) across = Vec3::UnitX();
    d = cos_max * Vec3::UnitZ() + std::sin(m.max_cone_rad) * across.normalized();
  }
  const double along = std::max(local.dot(d), 0.0);  // the goal's distance along that direction
  JointState q = inverse_from_tip(t, t.pivot_m + t.rotation * d, previous);
  q.insertion_m = std::clamp(along, m.min_insertion_m, m.max_insertion_m);
  return q;
}

MouseKeyboardDevice::MouseKeyboardDevice(std::array<Trocar, kHandles> trocars,
                                         const MouseMapping& m)
    : m_trocars(trocars), m_map(m), m_goal(m.rest), m_q(m.rest) {
  for (std::size_t h = 0; h < kHandles; ++h)
    m_seen.jaw_fraction[h] = m.jaw_max_rad[h] > 0.0 ? m.rest[h].jaw_rad / m.jaw_max_rad[h] : 0.0;
  m_input.store(m_seen);
  m_seat_out.rest = m.rest;
  m_seat_out.jaw_max_rad = m.jaw_max_rad;
  m_seat.store(m_seat_out);
}

void MouseKeyboardDevice::reseat(std::size_t h, const JointState& rest, double jaw_max_rad,
                                 const Quat& to_handle) {
  ++m_seat_out.generation[h];
  m_seat_out.rest[h] = rest;
  m_seat_out.jaw_max_rad[h] = jaw_max_rad;
  m_seat_out.to_handle[h] = {to_handle.w(), to_handle.x(), to_handle.y(), to_handle.z()};
  m_seat.store(m_seat_out);
}

void MouseKeyboardDevice::admit(std::size_t h) {
  if (m_seat_out.admitted[h] == m_seat_out.generation[h]) return;
  m_seat_out.admitted[h] = m_seat_out.generation[h];
  m_seat.store(m_seat_out);
}

// The handle draws back to its port and heads for the new instrument's rest, jaws closed.
void MouseKeyboardDevice::take_seat(std::size_t h, const MouseSeat& seat) {
  if (seat.generation[h] == m_generation[h]) return;
  m_generation[h] = seat.generation[h];
  m_map.rest[h] = seat.rest[h];
  m_map.jaw_max_rad[h] = seat.jaw_max_rad[h];
  const auto& q = seat.to_handle[h];
  m_to_handle[h] = Quat(q[0], q[1], q[2], q[3]).normalized();
  m_goal[h] = seat.rest[h];
  m_goal[h].jaw_rad = 0.0;
  m_q[h] = m_goal[h];
  m_q[h].insertion_m = m_map.min_insertion_m;
  m_entering[h] = true;
  m_pressed_until[h] = 0.0;  // the exchange the button asked for is done
}

// The handle button: held for kPressS after each press of X.
std::uint32_t MouseKeyboardDevice::press(std::size_t h, const PointerInput& in, double now_s) {
  if (in.exchanges[h] != m_seen.exchanges[h]) m_pressed_until[h] = now_s + kPressS;
  return now_s < m_pressed_until[h] ? kExchangeButton : 0u;
}

void MouseKeyboardDevice::follow_input(std::size_t h, const PointerInput& in) {
  JointState& g = m_goal[h];
  if (in.homes[h] != m_seen.homes[h]) {
    const double jaw = g.jaw_rad;
    g = m_map.rest[h];
    g.jaw_rad = jaw;
  }
  const Vec3 move = m_to_handle[h] * Vec3(in.move_m[h][0] - m_seen.move_m[h][0],
                                          in.move_m[h][1] - m_seen.move_m[h][1],
                                          in.move_m[h][2] - m_seen.move_m[h][2]);
  if (move.squaredNorm() > 0.0) {
    const ToolState now = forward(m_trocars[h], g);
    g = reach(m_trocars[h], Vec3(now.tip_m[0], now.tip_m[1], now.tip_m[2]) + move, g, m_map);
  }
  g.insertion_m =
      std::clamp(g.insertion_m + (in.depth_steps[h] - m_seen.depth_steps[h]) * m_map.m_per_step,
                 m_map.min_insertion_m, m_map.max_insertion_m);
  g.roll_rad += (in.roll_steps[h] - m_seen.roll_steps[h]) * m_map.rad_per_step;
  g.jaw_rad = std::clamp(in.jaw_fraction[h], 0.0, 1.0) * m_map.jaw_max_rad[h];
}

// `held`: a reseated handle waits, drawn back, until the stage admits its instrument.
void MouseKeyboardDevice::ease(std::size_t h, double dt_s, bool held) {
  const JointState& g = m_goal[h];
  JointState& q = m_q[h];
  const double jaw = q.jaw_rad;
  const double a = m_map.ease_s > 0.0 ? 1.0 - std::exp(-dt_s / m_map.ease_s) : 1.0;
  q.pitch_rad += a * (g.pitch_rad - q.pitch_rad);
  q.yaw_rad += a * (g.yaw_rad - q.yaw_rad);
  q.roll_rad += a * (g.roll_rad - q.roll_rad);
  if (m_entering[h]) {  // along the port's axis at the entry speed
    const double step = held ? 0.0 : m_map.entry_speed_m_s * dt_s;
    m_entering[h] = held || std::abs(g.insertion_m - q.insertion_m) > step;
    q.insertion_m = m_entering[h]
                        ? q.insertion_m + std::copysign(step, g.insertion_m - q.insertion_m)
                        : g.insertion_m;
  } else {
    q.insertion_m += a * (g.insertion_m - q.insertion_m);
    if (a >= 1.0) q = g;  // exact, not within rounding
  }
  const double jaw_step = m_map.jaw_speed_rad_s * dt_s;
  q.jaw_rad = jaw + std::clamp(g.jaw_rad - jaw, -jaw_step, jaw_step);
}

bool MouseKeyboardDevice::poll(double now_s, DeviceSample& out) noexcept {
  const PointerInput in = m_input.load();
  const MouseSeat seat = m_seat.load();
  const double dt = m_seq == 0 ? 0.0 : std::max(now_s - m_last_s, 0.0);
  m_last_s = now_s;
  DeviceSample s;
  s.sequence = ++m_seq;
  s.time_s = now_s;
  for (std::size_t h = 0; h < kHandles; ++h) {
    take_seat(h, seat);
    follow_input(h, in);
    ease(h, dt, seat.admitted[h] != m_generation[h]);
    s.joints[h] = m_q[h];
    s.pose[h] = forward(m_trocars[h], m_q[h]);
    s.buttons[h] = in.buttons[h] | press(h, in, now_s);
  }
  m_seen = in;
  out = s;
  return true;
}

}  // namespace serosa::haptics
