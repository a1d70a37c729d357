// The "clips" stage (contact slot, after the tools touched): clip appliers place ligation clips
// and endoloops cinch suture loops (engine/clip.h, engine/endoloop.h: ligatures), which then hold
// the tissue they close on wherever that tissue goes. Appliers act when "clips" is listed,
// endoloops when "loops" is.
//
// - Placing: an applier that opened past kClipArmRad and closes to kClipCloseRad places a clip
//   in its jaws, over [kClipStart, kClipStart + kClipLength] beyond the hinge. It clamps every
//   node (surface and interior: a vessel is closed through) within kClipHalfWidth of the jaw
//   plane and inside the wedge of the opening it closed from. A clip that closes on no tissue
//   falls away: it is counted, not placed.
// - Cinching: an endoloop that opened past kLoopArmRad and closes to kLoopCloseRad ligates every
//   node within kLoopHalfWidth of its ring's plane and inside the ring as it was open. The loop
//   closes round them: its centre is theirs (in the plane), and they are pressed towards its axis
//   until they lie within kLoopTightRadius. A loop round no tissue slips off: counted, not placed.
// - Clamping: each clamped node is held (a Dirichlet node, like a grasper's) at its place in the
//   clip's frame, pressed across the clip over kClipSqueezeS (a loop: kLoopSqueezeS) until the
//   tissue between the legs is kClipGap thick (a loop's within kLoopTightRadius).
// - Carried by the tissue: from kClipSettleS (kLoopSettleS) on, the clip's frame follows the rigid
// motion that
//   best carries its anchors (the free nodes sharing a tet with a clamped node) from where they
//   were then to where they are now (engine/geometry/rigid_fit.h). A rigid motion of the tissue
//   moves the clip with it exactly; traction on the tissue drags it along.
// - Stapling: a stapler (engine/stapler.h) fires when its jaws close from an armed opening: it
//   lays two staple lines, each a ligature of kind kStaple that clamps every free node in its
//   band (kStapleLineOffset +- kStapleLineHalfWidth either side of the knife along the pin) inside
//   the wedge the jaws closed from, over [kStapleStart, kCartridgeLength]; pressed across to
//   kStapleGap over kStapleSqueezeS. This stage decides whether it fires: jaws closed on a placed
//   ligature (its centre line within its reach of the stapled region) misfire (refused: counted,
//   nothing laid), jaws closed on no tissue lay nothing (counted as dropped). The cutting stage,
//   later in the same step, divides between the lines only when this stage laid them.
// - A cut's clone of a clamped node is clamped too (closing scissors never cut through a clip:
//   the cutting stage reads the clips in the hand-off).
// Every placed clip is handed on each step (SimState::shared.clips) for the cutting stage, the
// renderer and the metrics.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/clip.h"
#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/stage.h"
#include "engine/stapler.h"
#include "engine/state_blocks.h"
#include "engine/tet_mesh.h"
#include "engine/tool_state.h"

namespace serosa::contact {

inline constexpr double kClipArmRad = 0.3;     ///< the jaws must open this wide first, rad
inline constexpr double kClipCloseRad = 0.05;  ///< closed this far, the clip is placed, rad
inline constexpr double kClipSqueezeS = 0.05;  ///< time the legs take to press the tissue, s
inline constexpr double kClipSettleS = 0.1;    ///< after this the tissue carries the clip, s
/// A loop's knot is pushed down more slowly than a clip's legs close: pressing a whole
/// cross-section to the loop's axis in 0.05 s strained the tissue so fast that the lagged
/// factor went stale at once (100 CG iterations a step over 40 steps in the default scene).
inline constexpr double kLoopSqueezeS = 0.25;  ///< time the knot takes to cinch the tissue, s
inline constexpr double kLoopSettleS = 0.3;    ///< after this the tissue carries the loop, s
/// Staple lines press a whole cross-section (an appendix's base), so as slowly as a loop.
inline constexpr double kStapleSqueezeS = 0.25;  ///< time the staples take to close, s
inline constexpr double kStapleSettleS = 0.3;    ///< after this the tissue carries the lines, s

[[nodiscard]] constexpr double squeeze_s(Clip::Kind kind) {
  return kind == Clip::Kind::kLoop     ? kLoopSqueezeS
         : kind == Clip::Kind::kStaple ? kStapleSqueezeS
                                       : kClipSqueezeS;
}
[[nodiscard]] constexpr double settle_s(Clip::Kind kind) {
  return kind == Clip::Kind::kLoop     ? kLoopSettleS
         : kind == Clip::Kind::kStaple ? kStapleSettleS
                                       : kClipSettleS;
}

/// Clips tool `tool` closed on no tissue, loops it cinched round none and stapler fires on none
/// (scene tool order; 0 for other tools and before the first step).
[[nodiscard]] std::int64_t clips_dropped(const SimState& state, std::size_t tool);
/// Stapler fires of tool `tool` refused because its jaws closed on a placed ligature.
[[nodiscard]] std::int64_t stapler_refused(const SimState& state, std::size_t tool);

class ClipStage final : public Stage {
 public:
  explicit ClipStage(const Scene& scene);

  [[nodiscard]] std::string_view name() const noexcept override { return "clips"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// The appliers' openings, the clips and what each clamps are SimState::blocks.clips; a
  /// restored block is checked against the scene and the mesh, and SharedState::clips rebuilt.
  void adopt(SimState& state) override;

 private:
  using Placed = ClipsBlock::Placed;

  enum class Role : std::uint8_t { kNone, kApplier, kLoop, kStapler };

  void place(const StepContext& ctx, SimState& state, std::size_t tool, const ToolState& ts);
  /// The free nodes a loop cinched now ligates, in p.nodes and p.local (its frame set).
  void cinch(const SimState& state, std::size_t tool, const ToolState& ts, Placed& p) const;
  /// The free nodes between a closing applier's jaws, in p.nodes and p.local.
  void clamp_between_jaws(const SimState& state, std::size_t tool, const ToolState& ts,
                          Placed& p) const;
  /// Fires a stapler: refuses on a ligature, else lays the staple lines that clamp tissue.
  void staple(const StepContext& ctx, SimState& state, std::size_t tool, const ToolState& ts,
              double opening_rad);
  /// The free nodes in staple line k's band between the jaws, in p.nodes and p.local (its frame
  /// set).
  static void clamp_staple_line(const SimState& state, const StaplerJaws& jaws, int k, Placed& p);
  /// The anchors and the groups around p's nodes.
  static void find_anchors(const TetMesh& mesh, Placed& p);
  void clamp_clones(SimState& state);
  /// After a cut: drops the anchors that share no tet with a clamped node any more (the cut took
  /// them to the other side), so a piece cut free beside the clip does not drag it.
  static void prune_anchors(const TetMesh& mesh, Placed& p);
  void carry(Placed& p, const SimState& state, double age_s);
  void hold(Placed& p, SimState& state, double age_s) const;
  void publish(SimState& state) const;

  std::vector<Role> m_role;  // (tools) what it places, if anything
  std::vector<Vec3> m_to;    // scratch: the anchors now, for the fit
};

}  // namespace serosa::contact
