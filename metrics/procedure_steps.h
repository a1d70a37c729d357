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

#include "engine/math.h"
#include "engine/scene.h"
#include "engine/sim_state.h"
#include "metrics/procedure_errors.h"

namespace serosa {
class StateWriter;
class StateReader;
}  // namespace serosa

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

struct ProcedureStep {
  std::string_view name;  ///< "expose", "divide_mesentery", ...
  bool done = false;
  double time_s = 0.0;     ///< when it was done (end of that step), s
  std::int64_t tool = -1;  ///< the tool that did it (index into Scene::tools); -1: none known
};

class ProcedureSteps {
 public:
  ProcedureSteps() = default;
  /// tools: each tool's name (scene order), for the report.
  ProcedureSteps(ProcedureGroupIds ids, std::vector<std::string> tools);

  [[nodiscard]] bool active() const noexcept { return m_on; }
  /// Looks at the end of a solver step (time_s): grasps, ligatures, this step's cuts.
  void step(double time_s, const SimState& state, ProcedureErrors& errors);

  [[nodiscard]] const std::array<ProcedureStep, kProcedureSteps.size()>& steps() const noexcept {
    return m_steps;
  }
  [[nodiscard]] bool completed() const;
  /// The freed specimen's share of the specimen group's rest volume (0 before the transection).
  [[nodiscard]] double specimen_fraction() const noexcept { return m_fraction; }
  /// metrics["procedure"] = {"steps": [{"name", "done", "time_s", "tool"}], "completed",
  /// "specimen_volume_fraction"}.
  void report(nlohmann::json& metrics) const;

  void save(StateWriter& out) const;
  void restore(StateReader& in);

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
  std::array<ProcedureStep, kProcedureSteps.size()> m_steps;
  double m_time = 0.0;  // the step being looked at, s
  // From the first step's mesh (saved):
  bool m_ready = false;
  Vec3 m_origin = Vec3::Zero();  // rest: the mean of the nodes the specimen shares with the base
  std::int32_t m_far = -1;       // the specimen's node farthest from there at rest
  double m_volume = 0.0;         // the specimen group's rest volume, m^3
  // After the transection (saved):
  Vec3 m_freed_at = Vec3::Zero();  // where the specimen was freed (the cut's centre), m
  double m_fraction = 0.0;
  bool m_dropped = false;
  // Caches (rebuilt):
  std::uint64_t m_version = ~0ull;          // topology the node roles were taken from
  std::vector<std::uint8_t> m_role;         // (n) bit 0: specimen node, bit 1: base node
  std::vector<std::uint8_t> m_in_specimen;  // (n) 1: in the freed specimen's piece
  bool m_pieces_stale = true;
};

}  // namespace serosa::metrics
