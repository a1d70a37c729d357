// Trocar friction: the valve and seal of a port drag on the shaft sliding through it. Rendered on
// the insertion axis at 1 kHz from the handle's insertion velocity v, as a smoothed Coulomb term
// plus a viscous one:
//     F = -(coulomb_N * tanh(v / smooth_mps) + viscous_Nspm * v)          (N, along the shaft)
// It always opposes the motion (F v <= 0: it only takes energy out, so it cannot destabilize the
// loop) and is zero at rest. v is the insertion rate between device samples, low-pass filtered
// (time constant filter_s): the encoder's 50 um steps make the raw difference noisy.
#pragma once

namespace serosa::haptics {

struct TrocarFrictionParams {
  double coulomb_N = 0.3;     ///< sliding friction of the seal, N
  double smooth_mps = 0.01;   ///< speed over which the Coulomb term builds up, m/s (> 0)
  double viscous_Nspm = 2.0;  ///< viscous drag, N s/m
  double filter_s = 0.02;     ///< velocity low-pass time constant, s
};

class TrocarFriction {
 public:
  /// Friction force for insertion velocity v (m/s), N.
  [[nodiscard]] static double force_N(double v_mps, const TrocarFrictionParams& p) noexcept;

  /// Forgets the motion (after a gap or a replug): the next sample starts from rest.
  void reset() noexcept {
    m_have = false;
    m_v = 0.0;
  }
  /// A new device sample: the insertion (m) at time_s (s).
  void sample(double insertion_m, double time_s, const TrocarFrictionParams& p) noexcept;
  [[nodiscard]] double velocity_mps() const noexcept { return m_v; }
  /// The friction force at the filtered velocity, N.
  [[nodiscard]] double force_N(const TrocarFrictionParams& p) const noexcept {
    return force_N(m_v, p);
  }

 private:
  bool m_have = false;
  double m_insertion_m = 0.0;
  double m_time_s = 0.0;
  double m_v = 0.0;  // filtered insertion velocity, m/s
};

}  // namespace serosa::haptics
