// The steps of an appendectomy, followed as the trainee does them (the metrics stage keeps them):
//   expose               a grasper holds the specimen (the appendix) and has lifted what it
//                        holds kExposeLift from where it lay
//   divide_mesentery     no piece of the mesentery (the mesoappendix with its artery) joins the
//                        base (the cecum) to the specimen beyond kBaseZone from the base: the
//                        fold is divided down to the base (the artery's clip is judged by the
//                        bleeding error, metrics/procedure_errors.h)
//   secure_base          a loop or a staple line ligates the specimen within kBaseZone of the
//                        base (at rest)
//   transect             a cut leaves the specimen's far end in a piece without the base (a
//                        stapler secures and transects in one fire: its lines are laid in the
//                        step its knife cuts between them)
//   extract              that piece, the freed specimen, was carried kExtractDistance from where
//                        it was freed
// Each step is done once, with when and by which tool. The errors the steps can make go to the
// procedure's error list: a transection with no loop or staple line on the stump's side of it
// (above the securing), and a freed specimen no grasper holds before it is extracted (dropped).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/bound_block.h"
#include "engine/math.h"
#include "engine/metrics_block.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "metrics/procedure_errors.h"

namespace serosa::metrics {

inline constexpr double kExposeLift = 0.01;       ///< m
inline constexpr double kBaseZone = 0.015;        ///< m, at rest, from the specimen's base
inline constexpr double kExtractDistance = 0.04;  ///< m

/// The group ids the steps are judged on.
struct ProcedureGroupIds {
  int specimen = -1;
  int base = -1;
  std::vector<int> mesentery;  ///< the fold's groups: the mesentery's and its artery's
};

using serosa::ProcedureStep;

class ProcedureSteps {
 public:
  ProcedureSteps() = default;
  /// tools: each tool's name (scene order), for the report.
  ProcedureSteps(ProcedureGroupIds ids, std::vector<std::string> tools);

  [[nodiscard]] bool active() const noexcept { return m_on; }
  /// Looks at the end of a solver step (time_s): grasps, ligatures, this step's cuts.
  void step(double time_s, const SimState& state, ProcedureErrors& errors);

  [[nodiscard]] const std::array<ProcedureStep, kProcedureSteps.size()>& steps() const noexcept {
    return m_b->steps;
  }
  [[nodiscard]] bool completed() const;
  /// The freed specimen's share of the specimen group's rest volume (0 before the transection).
  [[nodiscard]] double specimen_fraction() const noexcept { return m_b->fraction; }
  /// metrics["procedure"] = {"steps": [{"name", "done", "time_s", "tool"}], "completed",
  /// "specimen_volume_fraction"}.
  void report(nlohmann::json& metrics) const;

  /// Reads and writes the SimState block `b` from now on (engine/bound_block.h).
  void bind(StepsBlock& b) noexcept { m_b.bind(b); }
  /// The bound block was restored: names its steps and drops the caches taken from the mesh.
  void adopt();
  /// The zero block it starts a state's from.
  [[nodiscard]] const StepsBlock& unbound_block() const noexcept { return m_b.unbound(); }

 private:
  enum Index : std::size_t { kExpose, kDivide, kSecure, kTransect, kExtract };

  void init(const TetMesh& mesh);
  void refresh_groups(const TetMesh& mesh);
  void expose(const SimState& state);
  void divide(const SimState& state);
  void secure(const SimState& state);
  void transect(const SimState& state, double time_s, ProcedureErrors& errors);
  void follow_specimen(const SimState& state, double time_s, ProcedureErrors& errors);
  void mark(Index i, double time_s, std::int64_t tool);
  [[nodiscard]] std::int64_t holder(const SimState& state) const;

  bool m_on = false;
  ProcedureGroupIds m_ids;
  std::vector<std::string> m_tools;
  double m_time = 0.0;  // the step being looked at, s
  // Caches (rebuilt after a restore: adopt()):
  std::uint64_t m_version = ~0ull;          // topology the node roles were taken from
  std::vector<std::uint8_t> m_role;         // (n) bit 0: specimen node, bit 1: base node
  std::vector<std::uint8_t> m_in_specimen;  // (n) 1: in the freed specimen's piece
  bool m_pieces_stale = true;
  BoundBlock<StepsBlock> m_b;  // its block of the state
};

}  // namespace serosa::metrics
