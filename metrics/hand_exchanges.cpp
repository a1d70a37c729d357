#include "metrics/hand_exchanges.h"

#include "engine/instrument_hold.h"
#include "engine/state_codec.h"

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
  const bool first = !m_seen;  // the first holds are where the session starts, not exchanges
  for (std::size_t h = 0; h < m_held.size(); ++h) {
    const std::int32_t now = holder_of(h, m_held[h], tools);
    m_seen = m_seen || now >= 0;
    if (!first && now != m_held[h])
      m_exchanges.push_back({t_s, static_cast<std::uint8_t>(h), m_held[h], now});
    m_held[h] = now;
    if (now >= 0 && in_port(tools[static_cast<std::size_t>(now)])) m_out_s += dt_s;
  }
}

void HandExchanges::report(nlohmann::json& j, const std::vector<std::string>& names) const {
  if (!m_seen) return;
  const auto name = [&](std::int32_t i) {
    return i >= 0 && static_cast<std::size_t>(i) < names.size()
               ? nlohmann::json(names[static_cast<std::size_t>(i)])
               : nlohmann::json(nullptr);
  };
  nlohmann::json list = nlohmann::json::array();
  for (const Exchange& e : m_exchanges)
    list.push_back({{"t_s", e.t_s},
                    {"hand", e.hand == 0 ? "left" : "right"},
                    {"from", name(e.from)},
                    {"to", name(e.to)}});
  j["exchanges"] = list;
  j["out_of_body_s"] = m_out_s;
}

void HandExchanges::save(StateWriter& out) const {
  out.u32(static_cast<std::uint32_t>(m_held[0]));
  out.u32(static_cast<std::uint32_t>(m_held[1]));
  out.u8(m_seen ? 1 : 0);
  out.f64(m_out_s);
  out.u64(m_exchanges.size());
  for (const Exchange& e : m_exchanges) {
    out.f64(e.t_s);
    out.u8(e.hand);
    out.u32(static_cast<std::uint32_t>(e.from));
    out.u32(static_cast<std::uint32_t>(e.to));
  }
}

void HandExchanges::restore(StateReader& in) {
  m_held[0] = static_cast<std::int32_t>(in.u32());
  m_held[1] = static_cast<std::int32_t>(in.u32());
  m_seen = in.u8() != 0;
  m_out_s = in.f64();
  const std::uint64_t n = in.u64();
  if (n > in.left()) in.fail("too many exchanges");
  m_exchanges.clear();
  for (std::uint64_t k = 0; k < n; ++k) {
    Exchange e;
    e.t_s = in.f64();
    e.hand = in.u8();
    e.from = static_cast<std::int32_t>(in.u32());
    e.to = static_cast<std::int32_t>(in.u32());
    if (e.hand > 1) in.fail("an exchange by a third hand");
    m_exchanges.push_back(e);
  }
}

}  // namespace serosa::metrics
