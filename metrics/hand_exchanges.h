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

#include "engine/bound_block.h"
#include "engine/metrics_block.h"
#include "engine/tool_state.h"

namespace serosa::metrics {

using serosa::Exchange;

class HandExchanges {
 public:
  /// Follows this step's inputs (tools, scene order) at time t_s, the step lasting dt_s.
  void step(double t_s, double dt_s, const std::vector<ToolState>& tools);

  /// The tool hand h (0 left, 1 right) holds now, if any.
  [[nodiscard]] std::optional<std::size_t> held(std::size_t h) const {
    return m_b->held[h] < 0 ? std::nullopt : std::optional<std::size_t>(m_b->held[h]);
  }
  /// Whether any input so far named a hand.
  [[nodiscard]] bool hands_seen() const noexcept { return m_b->seen; }
  [[nodiscard]] const std::vector<Exchange>& exchanges() const noexcept { return m_b->exchanges; }
  [[nodiscard]] double out_of_body_s() const noexcept { return m_b->out_s; }

  /// "exchanges" and "out_of_body_s" into `j`, tools named by `names` (only once hands were seen).
  void report(nlohmann::json& j, const std::vector<std::string>& names) const;

  /// Reads and writes the SimState block `b` from now on (engine/bound_block.h).
  void bind(ExchangesBlock& b) noexcept { m_b.bind(b); }
  /// The zero block it starts a state's from.
  [[nodiscard]] const ExchangesBlock& unbound_block() const noexcept { return m_b.unbound(); }

 private:
  BoundBlock<ExchangesBlock> m_b;  // its block of the state
};

}  // namespace serosa::metrics
