#include "metrics/hand_exchanges.h"

#include "engine/instrument_hold.h"

namespace serosa::metrics {
namespace {

// The tool hand h holds now: the one that held it before if it still names the hand, else the
// first that names it, else none.
std::int32_t holder_of(std::size_t h, std::int32_t before, const std::vector<ToolState>& tools) {
  const Hand hand = h == 0 ? Hand::kLeft : Hand::kRight;
  if (before >= 0 && static_cast<std::size_t>(before) < tools.size() &&
      holder(tools[static_cast<std::size_t>(before)]) == hand)
    return before;
  for (std::size_t i = 0; i < tools.size(); ++i)
    if (holder(tools[i]) == hand) return static_cast<std::int32_t>(i);
  return -1;
}

}  // namespace

void HandExchanges::step(double t_s, double dt_s, const std::vector<ToolState>& tools) {
  const bool first = !m_b->seen;  // the first holds are where the session starts, not exchanges
  for (std::size_t h = 0; h < m_b->held.size(); ++h) {
    const std::int32_t now = holder_of(h, m_b->held[h], tools);
    m_b->seen = m_b->seen || now >= 0;
    if (!first && now != m_b->held[h])
      m_b->exchanges.push_back({t_s, static_cast<std::uint8_t>(h), m_b->held[h], now});
    m_b->held[h] = now;
    if (now >= 0 && in_port(tools[static_cast<std::size_t>(now)])) m_b->out_s += dt_s;
  }
}

void HandExchanges::report(nlohmann::json& j, const std::vector<std::string>& names) const {
  if (!m_b->seen) return;
  const auto name = [&](std::int32_t i) {
    return i >= 0 && static_cast<std::size_t>(i) < names.size()
               ? nlohmann::json(names[static_cast<std::size_t>(i)])
               : nlohmann::json(nullptr);
  };
  nlohmann::json list = nlohmann::json::array();
  for (const Exchange& e : m_b->exchanges)
    list.push_back({{"t_s", e.t_s},
                    {"hand", e.hand == 0 ? "left" : "right"},
                    {"from", name(e.from)},
                    {"to", name(e.to)}});
  j["exchanges"] = list;
  j["out_of_body_s"] = m_b->out_s;
}

}  // namespace serosa::metrics
