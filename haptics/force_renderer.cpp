#include "haptics/force_renderer.h"

#include <algorithm>
#include <cmath>

namespace serosa::haptics {
namespace {

Vec3 v3(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

}  // namespace

void ForceRenderer::reset() noexcept {
  m_have_prev = false;
  for (auto& f : m_last) f.setZero();
  m_last_jaw.fill(0.0);
}

double ForceRenderer::blend(double now_s) const noexcept {
  if (!m_have_prev) return 1.0;
  return std::clamp((now_s - m_blend_start_s) / m_blend_len_s, 0.0, 1.0);
}

void ForceRenderer::set_model(const ContactModel& m, double now_s) noexcept {
  if (m.step == 0) return;
  if (m_have_cur) {
    m_prev = m_cur;
    m_have_prev = true;
    m_blend_len_s = std::clamp(now_s - m_last_model_s, m_p.blend_min_s, m_p.blend_max_s);
  } else {
    m_have_prev = false;
  }
  m_cur = m;
  m_have_cur = true;
  m_blend_start_s = now_s;
  m_last_model_s = now_s;
}

Vec3 ForceRenderer::field_force(const ContactModel& m, std::size_t tool, const Vec3& x,
                                double max_stiffness_Npm) {
  const ToolContact& t = m.tools[tool];
  const std::uint32_t n = std::min<std::uint32_t>(t.n_contacts, kMaxContacts);
  double total_k = t.coupled ? m.coupling_stiffness_Npm : 0.0;
  for (std::uint32_t i = 0; i < n; ++i) total_k += t.contacts[i].stiffness_Npm;
  const double scale = total_k > max_stiffness_Npm ? max_stiffness_Npm / total_k : 1.0;
  Vec3 f = Vec3::Zero();
  if (t.coupled) f += scale * m.coupling_stiffness_Npm * (v3(t.sim_tip_m) - x);
  for (std::uint32_t i = 0; i < n; ++i) {
    const ContactPlane& c = t.contacts[i];
    const Vec3 nrm = v3(c.normal);
    const double depth = (v3(c.point_m) - x).dot(nrm);
    if (depth > 0.0 || std::isnan(depth)) f += scale * c.stiffness_Npm * depth * nrm;
  }
  return f + v3(t.held_pull_N) + v3(t.shaft_push_N);
}

bool ForceRenderer::render(std::size_t tool, const Vec3& x, double now_s, double dt_s,
                           Vec3& out) noexcept {
  Vec3 f = Vec3::Zero();
  if (m_have_cur) {
    f = field_force(m_cur, tool, x, m_p.max_stiffness_Npm);
    const double a = blend(now_s);
    if (a < 1.0) f = a * f + (1.0 - a) * field_force(m_prev, tool, x, m_p.max_stiffness_Npm);
  }
  if (!f.allFinite() || !x.allFinite()) {
    m_last[tool].setZero();
    out.setZero();
    return false;
  }
  // Clamp to the rated maximum.
  const double mag = f.norm();
  if (mag > m_p.rated_force_N) f *= m_p.rated_force_N / mag;
  // Slew limit against the previous output.
  const double max_step = m_p.slew_N_per_s * std::clamp(dt_s, 0.0, 2e-3);
  const Vec3 step = f - m_last[tool];
  const double s = step.norm();
  if (s > max_step) f = m_last[tool] + step * (max_step / s);
  m_last[tool] = f;
  out = f;
  return true;
}

bool ForceRenderer::jaw_torque(std::size_t tool, double now_s, double dt_s, double& out) noexcept {
  double t = 0.0;
  if (m_have_cur) {
    const double a = blend(now_s);
    t = m_cur.tools[tool].jaw_torque_Nm;
    if (a < 1.0) t = a * t + (1.0 - a) * m_prev.tools[tool].jaw_torque_Nm;
  }
  if (!std::isfinite(t)) {
    m_last_jaw[tool] = 0.0;
    out = 0.0;
    return false;
  }
  t = std::clamp(t, -m_p.rated_jaw_torque_Nm, m_p.rated_jaw_torque_Nm);
  const double max_step = m_p.jaw_slew_Nm_per_s * std::clamp(dt_s, 0.0, 2e-3);
  t = std::clamp(t, m_last_jaw[tool] - max_step, m_last_jaw[tool] + max_step);
  m_last_jaw[tool] = t;
  out = t;
  return true;
}

}  // namespace serosa::haptics
