#include "metrics/clip_placement.h"

#include <algorithm>
#include <limits>

#include "engine/state_codec.h"

namespace serosa::metrics {

void ClipPlacement::step(const std::vector<Clip>& clips) {
  if (!m_on) return;
  m_on_artery = 0;
  m_off_artery = 0;
  m_error = std::numeric_limits<double>::infinity();
  for (const Clip& c : clips) {
    if (c.kind != Clip::Kind::kClip) continue;
    if (std::find(c.groups.begin(), c.groups.end(), m_artery) == c.groups.end()) {
      ++m_off_artery;
      continue;
    }
    ++m_on_artery;
    if (m_target) m_error = std::min(m_error, (c.rest_centre_m - *m_target).norm());
  }
}

void ClipPlacement::report(nlohmann::json& metrics) const {
  if (!m_on) return;
  nlohmann::json& j = metrics["clips"];
  j["on_artery"] = m_on_artery;
  j["off_artery"] = m_off_artery;
  if (m_target)
    j["target_error_m"] = m_on_artery > 0 ? nlohmann::json(m_error) : nlohmann::json(nullptr);
}

void ClipPlacement::save(StateWriter& out) const {
  if (!m_on) return;
  out.u64(static_cast<std::uint64_t>(m_on_artery));
  out.u64(static_cast<std::uint64_t>(m_off_artery));
  out.f64(m_error);
}

void ClipPlacement::restore(StateReader& in) {
  if (!m_on) return;
  m_on_artery = static_cast<int>(in.u64());
  m_off_artery = static_cast<int>(in.u64());
  m_error = in.f64();
}

}  // namespace serosa::metrics
