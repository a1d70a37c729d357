// The metrics stage's block of the whole state (metrics/metrics_stage.h and the parts it follows
// the procedure with): the sums of the assessment so far. Plain data, SI units; (tools) per scene
// tool, (n) per mesh node. Listed field by field for the snapshot (engine/state_walk.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/math.h"

namespace serosa {

/// One instrument exchange: at t_s, `hand` (0 left, 1 right) put down `from` and took `to` (tool
/// indices; -1 for none).
struct Exchange {
  double t_s = 0.0;
  std::uint8_t hand = 0;
  std::int32_t from = -1;
  std::int32_t to = -1;
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.t_s), f(s.hand), f(s.from), f(s.to);
  }
};

/// The hands' exchanges (metrics/hand_exchanges.h).
struct ExchangesBlock {
  std::array<std::int32_t, 2> held{-1, -1};  ///< tool index per hand, -1 none
  bool seen = false;                         ///< an input named a hand
  std::vector<Exchange> exchanges;           ///< in the order they happened
  double out_s = 0.0;  ///< time the hands' instruments spent in their ports while held, s
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.held), f(s.seen), f(s.out_s), f(s.exchanges);
  }
};

/// An error of the procedure (metrics/procedure_errors.h).
struct ProcedureError {
  enum class Kind : std::uint8_t {
    kBleeding,
    kThermalInjury,
    kTransectionAboveSecuring,  ///< metrics/procedure_steps.h
    kSpecimenDropped,           ///< metrics/procedure_steps.h
  };
  Kind kind = Kind::kBleeding;
  double time_s = 0.0;          ///< simulated time of the step it happened in, s
  Vec3 where_m = Vec3::Zero();  ///< where: the cut tets' mean centroid, the first burnt node, m
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.kind), f(s.time_s), f(s.where_m);
  }
};

struct ErrorsBlock {
  std::vector<std::uint8_t> burnt;     ///< (n) protected nodes found coagulated so far
  std::uint64_t seen_coag = 0;         ///< the coagulation version looked at last
  bool counted = false;                ///< an injury counted since the pedal last went down
  std::vector<ProcedureError> errors;  ///< in the order they happened
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.burnt), f(s.seen_coag), f(s.counted), f(s.errors);
  }
};

/// One step of the procedure (the scene's kProcedureSteps, in order).
struct ProcedureStep {
  std::string_view name;  ///< "expose", "divide_mesentery", ... (the scene's; not saved)
  bool done = false;
  double time_s = 0.0;     ///< when it was done (end of that step), s
  std::int64_t tool = -1;  ///< the tool that did it (index into Scene::tools); -1: none known
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.done), f(s.time_s), f(s.tool);
  }
};

/// The procedure's steps (metrics/procedure_steps.h).
struct StepsBlock {
  std::array<ProcedureStep, 5> steps{};  ///< the scene's kProcedureSteps, in order
  bool ready = false;                    ///< the specimen's rest data below is taken
  Vec3 origin = Vec3::Zero();    ///< rest: the mean of the nodes the specimen shares with the base
  std::int32_t far = -1;         ///< the specimen's node farthest from there at rest
  double volume = 0.0;           ///< the specimen group's rest volume, m^3
  Vec3 freed_at = Vec3::Zero();  ///< where the specimen was freed (the cut's centre), m
  double fraction = 0.0;         ///< the freed specimen's share of its rest volume
  bool dropped = false;          ///< the freed specimen was let fall
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.steps), f(s.ready), f(s.origin), f(s.far), f(s.volume), f(s.freed_at), f(s.fraction),
        f(s.dropped);
  }
};

/// What a stretch of the run cost (metrics/step_splits.h).
struct StepSplit {
  double duration_s = 0.0;     ///< s
  std::vector<double> path_m;  ///< (tools) m
  double idle_s = 0.0;         ///< s
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.duration_s), f(s.idle_s), f(s.path_m);
  }
};

struct SplitsBlock {
  std::vector<StepSplit> done;  ///< (steps) each step's split; zero until it is done
  StepSplit open;               ///< since the last step done
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.done), f(s.open);
  }
};

/// The clips on the artery (metrics/clip_placement.h).
struct ClipPlacementBlock {
  std::int64_t on_artery = 0, off_artery = 0;
  double error = 0.0;  ///< m; +inf: no clip on the artery
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.on_artery), f(s.off_artery), f(s.error);
  }
};

/// The transfer of an object between graspers (metrics/transfer_watch.h).
struct TransferBlock {
  Vec3 centre = Vec3::Zero();         ///< the object's centre now, m
  std::vector<std::int64_t> holders;  ///< the graspers holding it now
  std::int64_t sole = -1;             ///< the last grasper that held it alone; -1: none yet
  std::int64_t handoffs = 0, drops = 0;
  std::vector<double> drop_times;  ///< s
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.centre), f(s.holders), f(s.sole), f(s.handoffs), f(s.drops), f(s.drop_times);
  }
};

struct MetricsBlock {
  bool begun = false;          ///< shaped by the stage's first step
  bool forces = false;         ///< a contact stage hands tool forces over
  double time = 0.0;           ///< s
  std::vector<double> path;    ///< (tools) path length of each tip, m
  std::vector<Vec3> last_tip;  ///< (tools) m
  bool have_last = false;
  std::vector<double> force_max, force_sum;  ///< (tools) N
  std::vector<std::int64_t> force_steps;     ///< (tools)
  std::vector<double> out_of_view_s;   ///< (tools) time each tip spent out of the scope's view, s
  std::vector<double> target_first_s;  ///< (k) when each view target was first centred, s; -1
  std::vector<double> recent;          ///< (window x tools) the last steps' tip moves, m
  std::uint64_t recent_at = 0;         ///< steps put into `recent` so far
  double peak_stress = 0.0;            ///< Pa
  double cut_volume = 0.0, collateral = 0.0, dev_weighted = 0.0, dev_max = 0.0;  ///< m^3, m
  double idle_s = 0.0, active_s = 0.0, bimanual_s = 0.0, force_over_s = 0.0;     ///< s
  std::int64_t cut_tets = 0;
  bool over_tear = false;                  ///< the last sample's peak stress was above tear stress
  std::vector<double> tear_times;          ///< s
  std::vector<std::uint8_t> last_in_port;  ///< (tools) 1: it waited in its port last step
  ExchangesBlock exchanges;
  ErrorsBlock errors;
  StepsBlock steps;
  SplitsBlock splits;
  ClipPlacementBlock clips;
  TransferBlock transfer;
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.begun), f(s.forces), f(s.time), f(s.path), f(s.last_tip), f(s.have_last), f(s.force_max),
        f(s.force_sum), f(s.force_steps), f(s.out_of_view_s), f(s.target_first_s), f(s.recent),
        f(s.recent_at), f(s.peak_stress), f(s.cut_volume), f(s.collateral), f(s.dev_weighted),
        f(s.dev_max), f(s.idle_s), f(s.active_s), f(s.bimanual_s), f(s.force_over_s), f(s.cut_tets),
        f(s.over_tear), f(s.tear_times), f(s.last_in_port), f(s.exchanges), f(s.errors), f(s.steps),
        f(s.splits), f(s.clips), f(s.transfer);
  }
};

}  // namespace serosa
