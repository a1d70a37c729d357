// The "metrics" stage (after surface): what trainees and instructors are scored on.
//
//   time_s                  simulated time of the run, s
//   path_length_m[tool]     sum of |tip(k) - tip(k-1)| over consumed inputs, m
//   cut.deviation_mean_m    rest-volume-weighted mean distance of the cut tets' centroids (at
//                           the moment of the cut) from the scene's planned cut line, m
//   cut.deviation_max_m     their largest distance, m
//   cut.volume_m3           rest volume of every tet a blade cut, m^3
//   cut.collateral_m3       the part of it farther than cut_band from the planned line, m^3
//   force_max_n / force_mean_n [tool]  magnitude of the tool's force on the tissue (contact,
//                           grasp, and closing scissor blades' shear load, contact/): largest,
//                           and mean over the steps in which it touched the tissue, N
//   peak_stress_pa          largest von Mises stress over tets and steps (engine/tissue_stress.h)
//   tears                   with [metrics] tear_stress: how many times the peak stress rose above
//                           it (sampled as the peak stress is), and when (tear_times_s), 1
//   idle_time_s             time in which no hand instrument (grasper, scissors) moved: every
//                           tip slower than kIdleSpeed over the last kIdleWindowS, s
//   bimanual_fraction       of the time some hand instrument moved, the part in which every hand
//                           instrument was at work: moving or holding tissue (1: both hands
//                           worked together throughout; 0 with fewer than two). With hands, the
//                           hand instruments are the two the hands hold at the time.
//   exchanges, out_of_body_s  with hands (inputs that name them): the instrument exchanges
//                           (metrics/hand_exchanges.h)
//   force_over_s            time in which some tool pressed on the tissue harder than the
//                           scene's force_limit, s
//   view_targets            with [metrics] view_targets: how many the endoscope centred (each
//                           within kTargetConeDeg of its view's axis, kTargetRange away at most,
//                           at some step), how many it missed, and when it had centred the last
//                           (time_s: the run's time while any is missed), s
//   out_of_view_s[tool]     time the instrument's tip (grasper, scissors) was out of the
//                           endoscope's view while the endoscope was posed (engine/scope_view.h);
//                           only in scenes with an endoscope, s
//   bleeding_events, thermal_injuries, errors   with [metrics] artery or protected: the
//                           procedure's errors (metrics/procedure_errors.h)
//   clips                   with [metrics] artery and effect clips: the clips on and off the
//                           artery, and how far from [metrics] clip_target
//                           (metrics/clip_placement.h)
//   transfer                with [metrics] transfer: the object's hand-offs, drops and placing
//                           (metrics/transfer_watch.h)
//   procedure               with [metrics] procedure: its steps, whether all are done, and the
//                           freed specimen's share of its volume (metrics/procedure_steps.h),
//                           and what each step cost: its duration, paths and idle time
//                           (metrics/step_splits.h)
// Without a planned cut line the deviation and collateral entries are absent (the volume stays).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/bound_block.h"
#include "engine/math.h"
#include "engine/metrics_block.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"
#include "engine/tissue_stress.h"
#include "metrics/clip_placement.h"
#include "metrics/hand_exchanges.h"
#include "metrics/procedure_errors.h"
#include "metrics/procedure_steps.h"
#include "metrics/step_splits.h"
#include "metrics/transfer_watch.h"

namespace serosa::metrics {

/// A tip slower than this is still (idle time, bimanual use), m/s: a hand holding an instrument
/// drifts by a millimetre or so a second.
inline constexpr double kIdleSpeed = 5e-3;
/// The speed is the tip's path over this much time before the step, over that time, s: whatever
/// drives the instrument, its pose may change in steps (a mouse read once a frame, a rig's
/// packets, a script from Python) rather than every solver step, and a hand in motion is not
/// idle between two of them.
inline constexpr double kIdleWindowS = 0.25;

/// Distance from p to the polyline (k >= 1 points), m.
[[nodiscard]] double distance_to_polyline(const Vec3& p, const std::vector<Vec3>& line);

/// A view target is centred when it lies within this angle of the view's axis, degrees ...
inline constexpr double kTargetConeDeg = 10.0;
/// ... and no farther from the scope's tip than this, m (a close enough look).
inline constexpr double kTargetRange = 0.12;

class MetricsStage final : public Stage {
 public:
  /// stress_every: peak stress is sampled every that many steps (1 = every step). The tools'
  /// forces come from the contact stage (SimState::events.tool_force_n, plus closing scissors'
  /// blade load from events.tool_reactions; without a contact stage, none are reported), the cuts
  /// from the cutting stage (SimState::events.cuts).
  /// group_names: the mesh's group ids by name (app::AssembledScene::group_names), which the
  /// procedure's errors need ([metrics] artery and protected name groups).
  MetricsStage(const Scene& scene, LameTable lame, std::int64_t stress_every = 1,
               const std::map<int, std::string>& group_names = {});

  [[nodiscard]] std::string_view name() const noexcept override { return "metrics"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// The sums so far (path lengths, forces, cut volumes, deviations, peak stress) are
  /// SimState::blocks.metrics; a restored block is checked against the scene and read from then on.
  void adopt(SimState& state) override;

  [[nodiscard]] nlohmann::json report() const;

  [[nodiscard]] double path_length_m(std::size_t tool) const { return m_b->path[tool]; }
  /// The largest force the tool put on the tissue so far, N (0 before any contact step).
  [[nodiscard]] double force_max_n(std::size_t tool) const { return m_b->force_max[tool]; }
  /// The tool's force on the tissue in the last step, N.
  [[nodiscard]] double load_n(std::size_t tool) const { return m_load[tool]; }
  /// Above this a tool's force counts as rough handling (the scene's force_limit), N.
  [[nodiscard]] double force_limit_n() const noexcept { return m_force_limit; }
  [[nodiscard]] double peak_stress_pa() const noexcept { return m_b->peak_stress; }
  /// Times the peak stress rose above the scene's tear stress (0 without one).
  [[nodiscard]] std::int64_t tears() const noexcept {
    return static_cast<std::int64_t>(m_b->tear_times.size());
  }
  [[nodiscard]] double time_s() const noexcept { return m_b->time; }
  [[nodiscard]] double cut_volume_m3() const noexcept { return m_b->cut_volume; }
  [[nodiscard]] double collateral_m3() const noexcept { return m_b->collateral; }
  [[nodiscard]] double deviation_max_m() const noexcept { return m_b->dev_max; }
  [[nodiscard]] double idle_time_s() const noexcept { return m_b->idle_s; }
  [[nodiscard]] double bimanual_fraction() const noexcept {
    return m_b->active_s > 0.0 ? m_b->bimanual_s / m_b->active_s : 0.0;
  }
  [[nodiscard]] double force_over_s() const noexcept { return m_b->force_over_s; }
  /// Time the tool's tip was out of the endoscope's view, s (0 without an endoscope).
  [[nodiscard]] double out_of_view_s(std::size_t tool) const { return m_b->out_of_view_s[tool]; }
  /// The scene's view targets the endoscope has not centred yet.
  [[nodiscard]] std::size_t targets_missed() const;
  /// When the endoscope had centred every view target, s; the run's time while any is missed.
  [[nodiscard]] double targets_time_s() const;
  [[nodiscard]] const ProcedureErrors& procedure_errors() const noexcept { return m_errors; }
  [[nodiscard]] const ProcedureSteps& procedure_steps() const noexcept { return m_steps; }
  [[nodiscard]] const ClipPlacement& clip_placement() const noexcept { return m_clips; }
  [[nodiscard]] const TransferWatch& transfer() const noexcept { return m_transfer; }
  /// The hands' instrument exchanges (empty without hands).
  [[nodiscard]] const HandExchanges& exchanges() const noexcept { return m_exchanges; }
  /// What each of the procedure's steps cost (inactive without [metrics] procedure).
  [[nodiscard]] const StepSplits& step_splits() const noexcept { return m_splits; }
  [[nodiscard]] double deviation_mean_m() const noexcept {
    return m_b->cut_volume > 0.0 ? m_b->dev_weighted / m_b->cut_volume : 0.0;
  }

 private:
  std::vector<std::string> m_names;
  std::vector<std::uint8_t> m_hand;  // (tools) 1: a hand instrument (not the endoscope)
  double m_force_limit;
  std::vector<Vec3> m_planned;
  double m_band;
  /// Accounts the step's time to each instrument whose tip the endoscope does not see.
  void add_view(const std::vector<ToolState>& tools, double dt_s);
  /// Accounts one cut: volume, deviation from the planned line, collateral.
  void add_cut(const CutEvent& cut);
  /// Idle, active and bimanual time and time over the force limit, from this step's moves (m,
  /// (tools)) and forces. Returns whether every hand instrument was idle.
  bool add_use(const std::vector<double>& moved, const std::vector<double>& load, double dt_s);
  /// Whether the tool counts as a hand's instrument now (idle time, bimanual use).
  [[nodiscard]] bool at_hand(std::size_t tool) const;
  /// Accounts a sample of the mesh's largest von Mises stress (Pa): the peak, and a tear when it
  /// rises above the tear stress.
  void add_stress(double now_pa);
  /// The mesh's largest von Mises stress now, Pa.
  [[nodiscard]] double peak_stress(const TetMesh& mesh);

  LameTable m_lame;
  std::int64_t m_stress_every;
  HandExchanges m_exchanges;
  std::optional<double> m_tear_stress;  // Pa
  std::vector<double> m_moved;          // (tools) this step's tip moves, m
  std::size_t m_window = 1;             // steps in kIdleWindowS
  std::vector<double> m_load;           // (tools) this step's force on the tissue, N
  std::optional<std::size_t> m_scope;   // the scene's first endoscope
  std::vector<Vec3> m_targets;          // (k) the scene's view targets, m
  // The rest data of the stress, refilled when the topology changes or a snapshot is restored.
  RestStress m_rest;
  std::uint64_t m_rest_version = 0;
  bool m_rest_valid = false;
  void publish_bleeds(SimState& state) const;
  /// Reads and writes `b` from now on, and its parts the watchers' (the first step shapes it).
  void bind(MetricsBlock& b);

  ProcedureErrors m_errors;
  ProcedureSteps m_steps;
  StepSplits m_splits;  // with the procedure's steps
  ClipPlacement m_clips;
  TransferWatch m_transfer;
  /// Follows the procedure's steps at the end of a step, splitting the run where one is done.
  void follow_steps(SimState& state);
  BoundBlock<MetricsBlock> m_b;  // its block of the state (the sums above are its)
};

}  // namespace serosa::metrics
