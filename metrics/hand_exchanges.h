// The instrument exchanges of a session, followed from the holder bits of the consumed inputs
// (engine/instrument_hold.h), so a replay finds the same ones:
//   exchanges             every time a hand took another instrument: [{t_s, hand, from, to}]
//                         (from or to null when the hand held nothing)
//   out_of_body_s         time the hands' instruments spent in their ports while held (an
//                         exchange's withdrawal and insertion), summed over hands, s
// A hand holds the instrument whose input names it; when two claim one hand, the one that held it
// before keeps it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/tool_state.h"

namespace serosa {
class StateWriter;
class StateReader;
}  // namespace serosa

namespace serosa::metrics {

/// One exchange: at t_s, `hand` (0 left, 1 right) put down `from` and took `to` (tool indices;
/// -1 for none).
struct Exchange {
  double t_s = 0.0;
  std::uint8_t hand = 0;
  std::int32_t from = -1;
  std::int32_t to = -1;
};

class HandExchanges {
 public:
  /// Follows this step's inputs (tools, scene order) at time t_s, the step lasting dt_s.
  void step(double t_s, double dt_s, const std::vector<ToolState>& tools);

  /// The tool hand h (0 left, 1 right) holds now, if any.
  [[nodiscard]] std::optional<std::size_t> held(std::size_t h) const {
    return m_held[h] < 0 ? std::nullopt : std::optional<std::size_t>(m_held[h]);
  }
  /// Whether any input so far named a hand.
  [[nodiscard]] bool hands_seen() const noexcept { return m_seen; }
  [[nodiscard]] const std::vector<Exchange>& exchanges() const noexcept { return m_exchanges; }
  [[nodiscard]] double out_of_body_s() const noexcept { return m_out_s; }

  /// "exchanges" and "out_of_body_s" into `j`, tools named by `names` (only once hands were seen).
  void report(nlohmann::json& j, const std::vector<std::string>& names) const;

  void save(StateWriter& out) const;
  void restore(StateReader& in);

 private:
  std::array<std::int32_t, 2> m_held{-1, -1};  // tool index per hand, -1 none
  bool m_seen = false;
  std::vector<Exchange> m_exchanges;
  double m_out_s = 0.0;
};

}  // namespace serosa::metrics
