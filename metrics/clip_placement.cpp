#include "metrics/clip_placement.h"

#include <algorithm>
#include <limits>

namespace serosa::metrics {

void ClipPlacement::step(const std::vector<Clip>& clips) {
  if (!m_on) return;
  m_b->on_artery = 0;
  m_b->off_artery = 0;
  m_b->error = std::numeric_limits<double>::infinity();
  for (const Clip& c : clips) {
    if (c.kind != Clip::Kind::kClip) continue;
    if (std::find(c.groups.begin(), c.groups.end(), m_artery) == c.groups.end()) {
      ++m_b->off_artery;
      continue;
    }
    ++m_b->on_artery;
    if (m_target) m_b->error = std::min(m_b->error, (c.rest_centre_m - *m_target).norm());
  }
}

void ClipPlacement::report(nlohmann::json& metrics) const {
  if (!m_on) return;
  nlohmann::json& j = metrics["clips"];
  j["on_artery"] = m_b->on_artery;
  j["off_artery"] = m_b->off_artery;
  if (m_target)
    j["target_error_m"] = m_b->on_artery > 0 ? nlohmann::json(m_b->error) : nlohmann::json(nullptr);
}

}  // namespace serosa::metrics
