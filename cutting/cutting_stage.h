// The "cutting" stage: scissors cut the organs along the exact path of their blades
// (docs/ARCHITECTURE.md "Cutting, in the paper's terms"). Each blade's edge runs from the jaw hinge
// to the blade tip (engine/tool_geometry.h); closing jaws sweep it. The swept polygon goes to
// cutting::cut_mesh (candidates from a TetBvh over current positions), the resulting TopologyDelta
// is applied to the mesh between FEM steps and handed on in SimState::events.cuts, from which the
// surface and metrics stages of this step and the FEM stage of the next update themselves.
//
// One closing stroke, one cut, however the scissors move while they close. Cut step by step,
// each step's sweep is a strip a fraction of a tet wide whose outline runs through every tet it
// meets: the cutting core opens those tets short of the blade or not at all and splits the same
// tets again at the next step (a stationary transection of the appendix grew from 3.8k to 245k
// tets in 18 steps and stayed one piece; moving 2 mm sideways while closing left it in one piece
// with 46 % more tets; rolling about the shaft grew it 90-fold). So the stage gathers the stroke
// (cutting/scissors_stroke.h: the blade edges of every step, pinned to the tissue they passed
// through) and cuts it once, when it ends, as the hull of the swept samples in their best-fit
// plane: one polygon across both blades when the jaws met, one per blade (up to where it stopped)
// otherwise. A stroke ends when the jaws close, when they open again as wide as the stroke began,
// or when the scissors are drawn more than kStrokeDriftTol away from where the jaws were most
// closed. So a pause, a partial reopening (a second bite at the same place), tremor and any motion
// while the jaws close keep the stroke: cut at a partial reopening, the two blades' polygons left
// outlines through the tissue that the next closing had to cross again, and the tissue stayed in
// one piece. A stroke whose swept surface bends (a roll of the wrist, a drift across the blade
// plane while the jaws close) is cut along that surface in one cut: the mesh is flattened onto
// the stroke's plane by the surface's height field for the cut alone (cutting/flat_cut.h), so
// the crack is one welded piecewise-planar surface through every tet the blades crossed. Cut as
// successive planar pieces instead, each crack ended inside the tets along the edge two pieces
// shared and left a bridge there, and overlapping the pieces to make the cracks cross doubled
// the tets and still left one piece. A stroke is cut in the plane instead when its surface
// would put the crack farther from the blades' path in the tissue than the plane does (a
// surface that folds over its plane, as a 3 rad roll; tremor) or flattening would turn a tet
// near it over; the per-stroke report says which (`bent`) and how far the crack lies from the
// blades' path in the tissue. A stroke opens when it
// ends rather than while the jaws close, and where the swept region is not convex (a blade
// drawn back while it closes), its hull is cut.
//
// A stapler (engine/stapler.h) divides with its knife when it fires (its jaws close from an armed
// opening): one cut, the knife's trapezoid in the jaws' closing plane between the two staple
// lines, across the wedge the jaws closed from, through cutting::cut_mesh like a scissors stroke.
// The clips stage, earlier in the same step, decides whether it fires (contact/clip_stage.h): the
// knife runs only when that stage laid this fire's staple lines, so a stapler closed on a
// ligature (refused) or on nothing cuts nothing. Its own lines lie beside the knife, never across
// it, so the clip guard is not asked about them.
//
// A hook (effect "cautery", engine/hook.h) divides the same way: while its pedal is down, its
// crook's path is one stroke (the same pinned samples), cut as one polygon when the pedal comes
// up. The nodes within kCoagulationRadius of the live crook and the nodes its cut creates are
// marked coagulated, and clones and cut points take their parents' marks
// (SimState::blocks.cutting.coagulated, for the renderer). Neither tool cuts through a clip
// (cutting/clip_guard.h).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "cutting/cut_method.h"
#include "cutting/flat_cut.h"
#include "cutting/scissors_stroke.h"
#include "engine/scene/scene.h"
#include "engine/stage.h"
#include "engine/stapler.h"
#include "engine/state_blocks.h"
#include "engine/tool_geometry.h"
#include "engine/tool_state.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {
class TetBvh;
}

namespace serosa::cutting {

/// Scissors whose hinge moves farther than this (m) while their jaws neither close nor open end
/// the stroke.
inline constexpr double kStrokeDriftTol = 2e-3;
/// Jaws closed to this angle (rad) or less have met: the stroke ends (0.075 mm apart at the tips;
/// a rig's reading of closed jaws need not be exactly 0).
inline constexpr double kStrokeClosedRad = 0.01;
/// Jaws that open again to within this (rad) of the opening their stroke began at end it.
inline constexpr double kStrokeReopenTol = 0.02;

#ifdef NDEBUG
inline constexpr bool kCheckEveryCutByDefault = false;
#else
inline constexpr bool kCheckEveryCutByDefault = true;  ///< debug builds check every cut
#endif

/// A hook's stroke samples its crook at least this often along its path, m.
inline constexpr double kHookSampleStep = 5e-4;

struct CuttingStageOptions {
  /// Follow the scissors (the scene lists "cutting").
  bool scissors = true;
  /// Follow the hooks (the scene lists "cautery"): while a hook's pedal is down, its crook's
  /// path is one stroke, cut when the pedal comes up, and the nodes within kCoagulationRadius of
  /// the live crook are coagulated (SimState::blocks.cutting.coagulated).
  bool hooks = false;
  /// Follow the staplers (the scene lists "cutting"; a stapler needs "clips" too): each fire's
  /// knife cut.
  bool staplers = true;
  /// Check every cut with cutting::check_cut (costly: copies the mesh). On in debug builds; tests
  /// and `serosa headless --validate-cuts` turn it on in the others.
  bool validate = kCheckEveryCutByDefault;
};

/// What one closing stroke did (current positions at the moment it was cut).
struct StrokeReport {
  std::uint64_t first_step = 0;   ///< step of its first sweep
  std::uint64_t last_step = 0;    ///< step it was cut at
  std::uint64_t steps = 0;        ///< steps in which the jaws closed
  std::uint64_t polygons = 0;     ///< polygons it was cut with (1: jaws met; 2: opened part way)
  std::uint64_t cuts = 0;         ///< of those, the ones that changed the mesh
  std::int64_t tets_crossed = 0;  ///< tets the polygons crossed (removed)
  std::int64_t tets_created = 0;  ///< tets added in their place
  std::int64_t pinned = 0;        ///< partial tets left welded (cutting/cut_mesh.h tets_pinned)
  double swept_area_m2 = 0.0;     ///< polygons ∩ the tets they crossed, m²
  double crack_area_m2 = 0.0;     ///< one side of the crack opened, m²
  double deviation_m = 0.0;       ///< farthest swept sample from the polygons' plane, m
  /// Cut along its bent swept surface (cutting/flat_cut.h) rather than in the polygons' plane.
  bool bent = false;
  /// Farthest swept sample inside the tissue from the crack cut (ScissorsStroke::
  /// crack_deviation), m: the crack's deviation from where the blades passed.
  double crack_deviation_m = 0.0;
  double min_quality = 1.0;  ///< smallest mean-ratio quality of the created tets (rest)
  /// The blades closed on a clip (cutting/clip_guard.h): the stroke cut nothing.
  bool on_clip = false;
};

/// Totals over the stage's life.
struct CuttingStageStats {
  std::uint64_t strokes = 0;            ///< closing strokes cut (each as one or two polygons)
  std::uint64_t sweeps = 0;             ///< polygons swept (closing jaws)
  std::uint64_t degenerate_sweeps = 0;  ///< strokes that gave no polygon (no motion, NaN)
  std::uint64_t strokes_on_clip = 0;    ///< strokes left uncut: their blades closed on a clip
  std::uint64_t hook_strokes = 0;       ///< of the strokes, a hook's (pedal down to pedal up)
  std::uint64_t stapler_fires = 0;      ///< of the strokes, a stapler's knife between its lines
  /// Stapler fires that laid no staple lines, so the knife did not run: jaws closed on a ligature
  /// (refused) or on no tissue (the clips stage counts which: refused, dropped).
  std::uint64_t stapler_fires_held = 0;
  std::int64_t coagulated_nodes = 0;  ///< nodes a live hook coagulated (clones included)
  std::uint64_t cuts = 0;             ///< polygons that changed the mesh
  std::int64_t tets_removed = 0;
  std::int64_t tets_added = 0;
  std::int64_t nodes_added = 0;
  std::int64_t degenerate_tets = 0;          ///< emitted tets of non-positive volume (must stay 0)
  std::uint64_t validated = 0;               ///< cuts checked (validate option)
  std::uint64_t invalid = 0;                 ///< cuts whose check failed
  std::vector<std::string> problems;         ///< first problems found by the checks (at most 20)
  std::vector<StrokeReport> stroke_reports;  ///< the first kMaxStrokeReports strokes, in order
};
inline constexpr std::size_t kMaxStrokeReports = 256;

class CuttingStage final : public Stage {
 public:
  /// Cuts with every tool of kind scissors in `scene`, by its [cutting] method (pattern, remove,
  /// snap: cutting/cut_method.h) and tolerance.
  explicit CuttingStage(const Scene& scene, CuttingStageOptions options = {});
  ~CuttingStage() override;

  [[nodiscard]] std::string_view name() const noexcept override { return "cutting"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// Each instrument's last pose and stroke in progress and the coagulation are
  /// SimState::blocks.cutting; a restored block is checked and the tet BVH rebuilt.
  void adopt(SimState& state) override;

  /// Cuts `polygon` (convex, planar, world coordinates, m) by the scene's [cutting] method in the
  /// next step, before the tools cut: a cut no tool made (CutEvent::tool is kNoTool), asked for
  /// by a program (serosa.Simulation.cut). It is not a stroke; the step hands it on like one.
  void queue_cut(const cutting::ConvexPolygon& polygon) { m_queued.push_back(polygon); }
  /// What each queued polygon did, in the step that cut them (empty after a step without).
  [[nodiscard]] const std::vector<StrokeReport>& queued_cuts() const noexcept {
    return m_queued_reports;
  }

  [[nodiscard]] const CuttingStageStats& stats() const noexcept { return m_stats; }
  [[nodiscard]] std::size_t num_scissors() const noexcept { return m_scissors.size(); }
  [[nodiscard]] std::size_t num_staplers() const noexcept { return m_staplers.size(); }

 private:
  using Follow = CuttingBlock::Follow;

  /// What a hook's electrode does this step: `now`, or with the current off where it left the
  /// tissue when it was withdrawn into its port.
  static ToolState live_hook(const Follow& h, const ToolState& now);
  /// Follows one hook: coagulates around its live crook, extends its stroke, cuts it when the
  /// pedal comes up.
  void follow_hook(const StepContext& ctx, SimState& state, std::size_t tool, Follow& h,
                   const ToolState& now);
  /// Marks the nodes within kCoagulationRadius of [a, b] coagulated.
  void coagulate(const StepContext& ctx, SimState& state, const Vec3& a, const Vec3& b);
  /// Marks the nodes the cuts from `first_cut` on created (a hook's: its wound is coagulated).
  void coagulate_cut(SimState& state, std::size_t first_cut);
  /// Gives the new nodes of this step's cuts the marks of their parents.
  void inherit_coagulation(SimState& state, std::size_t first_cut);
  /// A stapler fired from `opening_rad`: its knife cuts between the lines laid this step.
  void fire(const StepContext& ctx, SimState& state, std::size_t tool, const ToolState& ts,
            double opening_rad);
  /// Cuts a finished stroke's polygons, unless they meet a clip; reports it.
  void cut_stroke(const StepContext& ctx, SimState& state, std::size_t tool,
                  const StrokePolygons& polygons, StrokeReport& report);
  /// Follows one scissors from `before` to `now`: begins, extends or ends its stroke.
  void follow(const StepContext& ctx, SimState& state, std::size_t tool, Follow& s,
              const ToolState& before, const ToolState& now);
  /// Adds the sweep before -> now to the stroke (begun here when there is none).
  void extend(const StepContext& ctx, const SimState& state, Follow& s, const ToolState& before,
              const ToolState& now);
  /// Cuts the stroke as it stands with the jaws at `end`, reports it and forgets it.
  void end_stroke(const StepContext& ctx, SimState& state, std::size_t tool, Follow& s,
                  ToolState end);
  /// A bent stroke's flattened positions, when its surface can be cut along and the crack then
  /// lies nearer the blades' path than the plane (std::nullopt: cut in the plane). Sets the
  /// report's bent and crack_deviation_m.
  std::optional<FlattenedPositions> flattening(const StepContext& ctx, SimState& state,
                                               const StrokePolygons& polygons,
                                               StrokeReport& report);
  /// Cuts one polygon (in flattened positions when `flat` is given); adds what it did to
  /// `report`.
  void cut(const StepContext& ctx, SimState& state, std::size_t tool, int blade,
           const cutting::ConvexPolygon& polygon, FlattenedPositions* flat, StrokeReport& report);
  void refresh_bvh(const StepContext& ctx, const TetMesh& mesh);
  /// Cuts the polygons queue_cut asked for.
  void cut_queued(const StepContext& ctx, SimState& state);
  std::vector<std::size_t> m_scissors;           // tool index of each scissors (SimState::tools)
  std::vector<cutting::ConvexPolygon> m_queued;  // queue_cut's, cut in the next step
  std::vector<StrokeReport> m_queued_reports;    // what they did
  std::vector<std::size_t> m_hooks;              // and of each hook
  std::vector<std::size_t> m_staplers;           // and of each stapler
  std::vector<std::int32_t> m_near;              // scratch: tets near a live crook
  std::vector<std::int32_t> m_scratch;           // scratch: a stroke's tree queries
  cutting::CutOptions m_cut_options;
  CutMethod m_method = CutMethod::kPattern;  // the scene's [cutting] method
  bool m_swept_strokes = true;               // [cutting] strokes = "swept"
  CuttingStageOptions m_options;
  std::unique_ptr<cutting::TetBvh> m_bvh;
  std::uint64_t m_bvh_version = 0;
  std::uint64_t m_bvh_step = ~0ull;
  CuttingStageStats m_stats;
};

}  // namespace serosa::cutting
