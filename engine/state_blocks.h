// The stages' blocks of the whole state (docs/ARCHITECTURE.md "State"): what a stage carries
// from one step to the next that the mesh, the tools and the shared outputs do not hold and that
// cannot be derived from them. SimState owns one of each (SimState::blocks); a stage reads and
// writes its own during its step and keeps only what it can rebuild from the scene and the state
// (BVHs, factors, tables). A snapshot writes every block field by field through the list each
// block gives (engine/state_walk.h), so a field listed there is saved and restored with nothing
// more to write. A block stays empty when its stage is not built.
//
// Plain data, scene frame, SI units; (n) is per mesh node, (m) per tet, (tools) per scene tool.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/clip.h"
#include "engine/fem_block.h"
#include "engine/math.h"
#include "engine/metrics_block.h"
#include "engine/stapler.h"
#include "engine/tool_state.h"

namespace serosa {

/// Smoke (cutting/smoke_stage.h): the ring of puffs a hook's coagulation raised.
struct SmokeBlock {
  /// One puff.
  struct Puff {
    std::array<double, 3> at{};     ///< centre, m
    std::array<double, 2> drift{};  ///< sideways velocity in the plane across gravity, m/s
    double born_s = -1.0;           ///< when it rose, s; < 0: none
    template <class S, class F>
    static void each(S& s, F&& f) {
      f(s.at), f(s.drift), f(s.born_s);
    }
  };
  std::vector<Puff> puffs;         ///< (the stage's ring size) a ring; empty before its first step
  std::uint64_t next = 0;          ///< puffs raised so far (the ring's next slot, modulo)
  std::vector<std::uint8_t> seen;  ///< (n) coagulation marks already smoked, 1
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.puffs), f(s.next), f(s.seen);
  }
};

/// Bleeding (metrics/bleeding_stage.h): each bleeding of the artery and the blood it left.
struct BleedingBlock {
  struct Source {
    std::int64_t node = 0;                ///< the mesh node carrying the cut end
    double since_s = 0.0;                 ///< when it began, s
    double shed_m3 = 0.0;                 ///< blood shed so far, m^3
    double closed_s = -1.0;               ///< when it was closed, s; < 0: still bleeding
    std::array<double, 3> pool{};         ///< the pool's centre, m
    std::array<double, 3> pool_normal{};  ///< unit
    std::int64_t coagulated_near = 0;     ///< coagulated nodes near the cut end when it began
    template <class S, class F>
    static void each(S& s, F&& f) {
      f(s.node), f(s.since_s), f(s.shed_m3), f(s.closed_s), f(s.pool), f(s.pool_normal),
          f(s.coagulated_near);
    }
  };
  std::vector<Source> sources;  ///< (bleedings) in the order they began
  std::vector<float> stain;     ///< (n) how much blood stains each node, [0, 1]; the view reads it
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.sources), f(s.stain);
  }
};

/// Contact (contact/tool_contact_stage.h): what each grasper holds.
struct ContactBlock {
  struct Grasp {
    std::vector<std::int32_t> nodes;      ///< (g) grabbed node ids
    std::vector<Vec3> local;              ///< (g) their positions in the tool frame at the grab, m
    std::vector<std::uint8_t> was_fixed;  ///< (g) each node's own Dirichlet flag before the grab
    bool holding = false;
    /// a grasper: its widest opening since the last release; scissors: the opening the stroke
    /// began with, rad
    double widest_rad = 0.0;
    template <class S, class F>
    static void each(S& s, F&& f) {
      f(s.nodes), f(s.local), f(s.was_fixed), f(s.holding), f(s.widest_rad);
    }
  };
  std::vector<Grasp> grasps;  ///< (tools)
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.grasps);
  }
};

/// Clips (contact/clip_stage.h): every ligature placed and the appliers' triggers.
struct ClipsBlock {
  struct Placed {
    Clip clip;                          ///< as handed on (SharedState::clips)
    std::vector<std::int32_t> nodes;    ///< (c) clamped node ids
    std::vector<Vec3> local;            ///< (c) where each was in the clip's frame at placing, m
    double press = 1.0;                 ///< the across- (a loop's radial) scale, (0, 1]
    std::vector<std::int32_t> anchors;  ///< (a) free nodes sharing a tet with a clamped node
    std::vector<Vec3> anchor_ref;       ///< (a) their positions when the clip settled, m
    Vec3 ref_hinge = Vec3::Zero();      ///< the clip's hinge then, m
    Mat3 ref_frame = Mat3::Identity();  ///< and its frame
    bool settled = false;
    template <class S, class F>
    static void each(S& s, F&& f) {
      f(s.clip), f(s.nodes), f(s.local), f(s.press), f(s.anchors), f(s.anchor_ref), f(s.ref_hinge),
          f(s.ref_frame), f(s.settled);
    }
  };
  std::vector<double> widest_rad;        ///< (tools) widest opening since each one's last clip
  std::vector<std::int64_t> dropped;     ///< (tools) clips dropped (closed on nothing)
  std::vector<std::int64_t> refused;     ///< (tools) stapler fires on a ligature
  std::vector<StaplerTrigger> triggers;  ///< (tools) each stapler's jaw channel
  std::vector<Placed> placed;            ///< in the order placed
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.widest_rad), f(s.dropped), f(s.refused), f(s.triggers), f(s.placed);
  }
};

/// One sampled point of a stroke's swept surface (cutting/scissors_stroke.h).
struct StrokeSample {
  Vec3 x_m = Vec3::Zero();  ///< where it was swept, world, m
  std::int32_t blade = -1;  ///< 0 or 1: a blade tip; -1: the hinge (both blades)
  std::int32_t tet = -1;    ///< the tet it is pinned to, -1: none
  std::array<double, 4> bary{0.0, 0.0, 0.0, 0.0};  ///< its weights in that tet (may be < 0 outside)
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.x_m), f(s.blade), f(s.tet), f(s.bary);
  }
};

/// A closing stroke (or a hook's) in progress: what it swept so far.
struct StrokeRecord {
  ToolState start;                     ///< the pose it began at
  std::uint64_t topology_version = 0;  ///< the mesh's when it began
  std::uint64_t steps = 0;             ///< sweeps taken
  std::vector<StrokeSample> samples;   ///< in the order swept
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.start), f(s.topology_version), f(s.steps), f(s.samples);
  }
};

/// Cutting (cutting/cutting_stage.h): the instruments' strokes in progress and the coagulation.
struct CuttingBlock {
  struct Follow {
    std::optional<ToolState> before;     ///< pose consumed at the previous step
    std::optional<ToolState> paused;     ///< scissors: pose where its jaws last closed
    std::optional<StrokeRecord> stroke;  ///< the stroke in progress
    std::uint64_t first_step = 0;        ///< step of the stroke's first sweep
    template <class S, class F>
    static void each(S& s, F&& f) {
      f(s.before), f(s.paused), f(s.stroke), f(s.first_step);
    }
  };
  std::vector<Follow> scissors;          ///< (scissors of the scene, in scene order)
  std::vector<Follow> hooks;             ///< (hooks of the scene, in scene order)
  std::vector<StaplerTrigger> staplers;  ///< (staplers of the scene) each one's jaw channel
  /// (n) 1: a live hook coagulated the node, else 0; empty when no hook is simulated. The view,
  /// the smoke and the metrics read it.
  std::vector<std::uint8_t> coagulated;
  std::uint64_t coagulated_version = 0;  ///< changes whenever a mark is added
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.scissors), f(s.hooks), f(s.staplers), f(s.coagulated), f(s.coagulated_version);
  }
};

/// Every stage's block, named as the stage is (its snapshot section).
struct StageBlocks {
  FemBlock fem;
  ContactBlock contact;
  ClipsBlock clips;
  CuttingBlock cutting;
  MetricsBlock metrics;
  BleedingBlock bleeding;
  SmokeBlock smoke;
  /// Each block with its name, in snapshot order.
  template <class S, class F>
  static void each_named(S& s, F&& f) {
    f("fem", s.fem), f("contact", s.contact), f("clips", s.clips), f("cutting", s.cutting),
        f("metrics", s.metrics), f("bleeding", s.bleeding), f("smoke", s.smoke);
  }
};

}  // namespace serosa
