// Errors the scene detects in a procedure (the metrics stage keeps them):
// - bleeding: a cut (scissors, hook or a stapler's knife) through the artery's group while no
//   ligature clamps that group (a clipped or stapled artery counts as secured: a stapler lays its
//   lines in the step its knife cuts);
// - thermal injury: a live hook coagulating tissue of a protected group (the cecum wall): one
//   per press of the pedal in which it does.
// Each is counted and kept with its time, for the report, the assessment and the replay.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/bound_block.h"
#include "engine/math.h"
#include "engine/metrics_block.h"
#include "engine/sim_state.h"

namespace serosa::metrics {

using serosa::ProcedureError;

class ProcedureErrors {
 public:
  ProcedureErrors() = default;
  /// artery: the group id that bleeds; protected_groups: the ids a live hook must not burn.
  ProcedureErrors(std::optional<int> artery, std::vector<int> protected_groups);

  /// True when the scene names an artery or protected groups (else nothing is watched).
  [[nodiscard]] bool active() const noexcept { return m_artery || !m_protected.empty(); }
  /// Looks at this step's cuts, clips and coagulation marks (end of the step, time_s).
  void step(double time_s, const SimState& state);

  [[nodiscard]] const std::vector<ProcedureError>& errors() const noexcept { return m_b->errors; }
  [[nodiscard]] std::int64_t count(ProcedureError::Kind kind) const;
  /// An error another watcher found (the procedure's steps).
  void add(const ProcedureError& e) { m_b->errors.push_back(e); }
  /// The report's name of a kind: "bleeding", "thermal_injury", "transection_above_securing",
  /// "specimen_dropped".
  [[nodiscard]] static const char* kind_name(ProcedureError::Kind kind);
  /// {"bleeding_events", "thermal_injuries", "errors": [{"kind", "time_s", "where_m"}]}, and
  /// with the procedure's steps followed (`steps`), "transections_above_securing" and
  /// "specimens_dropped".
  void report(nlohmann::json& metrics, bool steps = false) const;
  void report(nlohmann::json& metrics) const;

  /// Reads and writes the SimState block `b` from now on (engine/bound_block.h).
  void bind(ErrorsBlock& b) noexcept { m_b.bind(b); }
  /// The bound block was restored: drops the caches taken from the mesh.
  void adopt() noexcept { m_prot_version = ~0ull; }
  /// The zero block it starts a state's from.
  [[nodiscard]] const ErrorsBlock& unbound_block() const noexcept { return m_b.unbound(); }

 private:
  void check_cuts(double time_s, const SimState& state);
  void check_burns(double time_s, const SimState& state);

  std::optional<int> m_artery;
  std::vector<int> m_protected;           // sorted
  std::vector<std::uint8_t> m_node_prot;  // (n) 1: a node of a protected group's tet
  std::uint64_t m_prot_version = ~0ull;   // topology the above was taken from
  BoundBlock<ErrorsBlock> m_b;            // its block of the state
};

}  // namespace serosa::metrics
