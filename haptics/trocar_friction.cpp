#include "haptics/trocar_friction.h"

#include <cmath>

namespace serosa::haptics {

double TrocarFriction::force_N(double v_mps, const TrocarFrictionParams& p) noexcept {
  return -(p.coulomb_N * std::tanh(v_mps / p.smooth_mps) + p.viscous_Nspm * v_mps);
}

void TrocarFriction::sample(double insertion_m, double time_s,
                            const TrocarFrictionParams& p) noexcept {
  const double dt = time_s - m_time_s;
  if (m_have && dt > 0.0) {
    const double raw = (insertion_m - m_insertion_m) / dt;
    const double a = dt / (p.filter_s + dt);
    m_v += a * (raw - m_v);
  }
  if (!m_have || dt > 0.0) {
    m_insertion_m = insertion_m;
    m_time_s = time_s;
  }
  m_have = true;
  if (!std::isfinite(m_v)) m_v = 0.0;
}

}  // namespace serosa::haptics
