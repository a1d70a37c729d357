// ForceRenderer: turns the solver's ContactModel into a smooth, bounded tip force at 1 kHz.
//
//   F_raw(x) = k_c (sim_tip - x)                       virtual coupling (when the tool is coupled)
//            + sum_i k_i max(0, (p_i - x) . n_i) n_i     local contact planes
//            + P                                        the grasped tissue's pull on the jaws
//            + S                                        the tissue's push on the shaft, at the tip
// evaluated at the device proxy x every tick, so contact stiffness is rendered at 1 kHz with the
// latest hand position while the solver runs at its own rate. When a new model arrives, the
// rendered force blends linearly from the previous model to the new one over the last observed
// solver period (clamped to [blend_min_s, blend_max_s]). The result is then
//   1. zeroed when any term is NaN or infinite (and the history reset),
//   2. clamped in magnitude to rated_force_N,
//   3. slew limited: |F(k) - F(k-1)| <= slew_N_per_s * dt per tick (default 1000 N/s, i.e. at
//      most 1 N per 1 ms tick), so a cut or a contact change never steps the handle force.
// Safety zeroing (unplug, stall, missing model) bypasses the slew limit: zero is immediate, and
// after reset() the force ramps back from zero at the slew limit. The jaw torque (tissue between
// closing blades) is blended, clamped and slew limited the same way (jaw_torque()), so the drop
// when the tissue gives way at a cut is felt as a bounded step.
#pragma once

#include <array>
#include <cstddef>
#include <limits>

#include "engine/math.h"
#include "haptics/contact_model.h"

namespace serosa::haptics {

struct ForceRendererParams {
  double rated_force_N = 8.0;    ///< maximum tip force magnitude per handle, N
  double slew_N_per_s = 1000.0;  ///< maximum rate of change of the rendered force, N/s
  double blend_min_s = 1e-3;     ///< shortest blend between two models, s
  double blend_max_s = 50e-3;    ///< longest blend between two models, s
  /// Largest total stiffness rendered (coupling plus contact planes), N/m: beyond it every term
  /// is scaled down together. The loop sets it to kPassivityMargin of the passivity bound 2 b / T
  /// of its device's damping b and its period T (HapticLoopConfig::device_damping_Nspm).
  double max_stiffness_Npm = std::numeric_limits<double>::infinity();
  double rated_jaw_torque_Nm = 0.2;  ///< maximum jaw torque magnitude, N m
  double jaw_slew_Nm_per_s = 10.0;   ///< maximum rate of change of the jaw torque, N m/s
};

/// The stiffness a device with damping b (N s/m) sampled with period T (s), the force held
/// between samples, renders passively below: 2 b / T, N/m (Colgate and Schenkel 1997). At the
/// bound itself a wall is marginal, so the loop keeps kPassivityMargin of it.
[[nodiscard]] inline double passivity_bound_Npm(double damping_Nspm, double period_s) noexcept {
  return 2.0 * damping_Nspm / period_s;
}
inline constexpr double kPassivityMargin = 0.8;

class ForceRenderer {
 public:
  explicit ForceRenderer(const ForceRendererParams& p = {}) : m_p(p) {}

  /// Forget the last output and any blend in progress (the current model stays): the next force
  /// starts from zero and ramps at the slew limit.
  void reset() noexcept;
  /// A new model (m.step differs from the current one) arrived at now_s.
  void set_model(const ContactModel& m, double now_s) noexcept;
  /// True once a model with step != 0 was set.
  [[nodiscard]] bool has_model() const noexcept { return m_have_cur; }

  /// Unfiltered force of model m on tool `tool` at proxy x (N), its stiffnesses scaled to at most
  /// max_stiffness_Npm in total; NaN propagates.
  [[nodiscard]] static Vec3 field_force(
      const ContactModel& m, std::size_t tool, const Vec3& x,
      double max_stiffness_Npm = std::numeric_limits<double>::infinity());

  /// Rendered force for `tool` at proxy x and time now_s, dt_s after the previous tick. Returns
  /// false and writes zero when the force is not finite (the caller counts it); otherwise the
  /// blended, clamped, slew-limited force.
  bool render(std::size_t tool, const Vec3& x, double now_s, double dt_s, Vec3& out) noexcept;

  /// Rendered jaw torque for `tool` at now_s, dt_s after the previous tick (N m, + opens):
  /// the models' jaw torques blended, clamped and slew limited. Non-finite gives false and zero.
  bool jaw_torque(std::size_t tool, double now_s, double dt_s, double& out) noexcept;

  /// Sets the last output of a tool to zero (a safety zero outside render()).
  void zero_output(std::size_t tool) noexcept {
    m_last[tool].setZero();
    m_last_jaw[tool] = 0.0;
  }

  [[nodiscard]] const ForceRendererParams& params() const noexcept { return m_p; }

 private:
  ForceRendererParams m_p;
  ContactModel m_prev{};
  ContactModel m_cur{};
  bool m_have_prev = false;
  bool m_have_cur = false;
  double m_blend_start_s = 0.0;
  double m_blend_len_s = 1e-3;
  double m_last_model_s = 0.0;
  std::array<Vec3, kHandles> m_last{Vec3::Zero(), Vec3::Zero()};
  std::array<double, kHandles> m_last_jaw{};

  [[nodiscard]] double blend(double now_s) const noexcept;  // weight of the current model
};

}  // namespace serosa::haptics
