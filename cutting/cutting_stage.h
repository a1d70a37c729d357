// The "cutting" stage: scissors cut the organs along the exact path of their blades
// (docs/ARCHITECTURE.md "Cutting, in the paper's terms"). Each blade's edge runs from the jaw hinge
// to the blade tip (engine/tool_geometry.h); closing jaws sweep it. The swept polygon goes to
// cutting::cut_mesh (candidates from a TetBvh over current positions), the resulting TopologyDelta
// is applied to the mesh between FEM steps and handed on in SimState::handoff.cuts, from which the
// surface and metrics stages of this step and the FEM stage of the next update themselves.
//
// One closing stroke, one cut. While the scissors stay put (hinge within kStrokeHingeTol, blade
// plane within kStrokeAngleTol of where the stroke began) the per-step sweeps of one stroke are
// all in the same plane, side by side: cut one by one, each is a strip a fraction of a tet wide
// whose outline runs through every tet it meets, so the cutting core opens those tets short of
// the blade or not at all, and splits the same tets again at the next step (the
// appendix transection grew from 3.8k to 245k tets in 18 steps and stayed one piece). So the
// stage accumulates the stroke and cuts once, with the whole swept sector (hinge plus points on
// the arc of the blade tips, convex), when the jaws open again, close completely, or the
// scissors move off the stroke's plane; a stroke that closed fully is a single sector across
// both blades. A pause keeps the stroke: cut at the pause, the two blades' sectors leave a notch
// between them that the rest of the closing then cuts as a third polygon next to the first two,
// and the appendix stayed in one piece; the price is that the wound opens only when the stroke
// ends (the jaws close or open, or the scissors move). Steps in which the scissors move while
// closing sweep per step as before (cutting/blade_sweep.h: the quad between the two poses of each
// blade). cutting::ProgressiveCut would give the same single-cut result step by step (the wound
// opening while the jaws close), but the two blades sweep two sectors that are one convex region
// only once the jaws meet, and moving strokes sweep quads in changing planes, so the stage does not
// use it (yet).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cutting/blade_sweep.h"
#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "cutting/cut_method.h"
#include "engine/scene.h"
#include "engine/stage.h"
#include "engine/tool_geometry.h"
#include "engine/tool_state.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {
class TetBvh;
}

namespace serosa::cutting {

/// Scissors that move less than this (hinge, m) and turn less than kStrokeAngleTol (rad) while
/// their jaws close are stationary: the stroke is cut as one sector.
inline constexpr double kStrokeHingeTol = 5e-4;
inline constexpr double kStrokeAngleTol = 0.02;
/// The sector's arc is drawn with points at most this far apart in angle, rad.
inline constexpr double kStrokeArcStep = 0.05;

/// The polygon a blade edge of length `length_m` sweeps turning about `frame.hinge` in the jaw
/// plane from angle a0 to angle a1 (rad from the shaft axis, towards frame.side): the hinge and
/// points on the arc of the tip. std::nullopt when it has no area.
[[nodiscard]] std::optional<cutting::ConvexPolygon> sector_polygon(const ToolFrame& frame,
                                                                   double a0, double a1,
                                                                   double length_m);

#ifdef NDEBUG
inline constexpr bool kCheckEveryCutByDefault = false;
#else
inline constexpr bool kCheckEveryCutByDefault = true;  ///< debug builds check every cut
#endif

struct CuttingStageOptions {
  /// Check every cut with cutting::check_cut (costly: copies the mesh). On in debug builds; tests
  /// and `serosa headless --validate-cuts` turn it on in the others.
  bool validate = kCheckEveryCutByDefault;
};

/// Totals over the stage's life.
struct CuttingStageStats {
  std::uint64_t strokes = 0;            ///< stationary closing strokes cut as one sector
  std::uint64_t sweeps = 0;             ///< blade polygons swept (closing jaws)
  std::uint64_t degenerate_sweeps = 0;  ///< sweeps that gave no polygon (no motion, NaN)
  std::uint64_t cuts = 0;               ///< polygons that changed the mesh
  std::int64_t tets_removed = 0;
  std::int64_t tets_added = 0;
  std::int64_t nodes_added = 0;
  std::int64_t degenerate_tets = 0;   ///< emitted tets of non-positive volume (must stay 0)
  std::uint64_t validated = 0;        ///< cuts checked (validate option)
  std::uint64_t invalid = 0;          ///< cuts whose check failed
  std::vector<std::string> problems;  ///< first problems found by the checks (at most 20)
};

class CuttingStage final : public Stage {
 public:
  /// Cuts with every tool of kind scissors in `scene`, by its [cutting] method (pattern, remove,
  /// snap: cutting/cut_method.h) and tolerance.
  explicit CuttingStage(const Scene& scene, CuttingStageOptions options = {});
  ~CuttingStage() override;

  [[nodiscard]] std::string_view name() const noexcept override { return "cutting"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// Each scissors' last pose and the stroke in progress (the tet BVH is rebuilt).
  void save(StateWriter& out) const override;
  void restore(StateReader& in, SimState& state) override;

  [[nodiscard]] const CuttingStageStats& stats() const noexcept { return m_stats; }
  [[nodiscard]] std::size_t num_scissors() const noexcept { return m_scissors.size(); }

 private:
  void cut(const StepContext& ctx, SimState& state, std::size_t tool, int blade,
           const cutting::ConvexPolygon& polygon);

  /// Cuts the sector stroke.start -> the given closing angle (rad) and forgets the stroke.
  void flush_stroke(const StepContext& ctx, SimState& state, std::size_t tool,
                    const ToolState& start, double end_jaw_rad);

  struct Scissors {
    std::size_t tool = 0;             // index into Scene::tools / SimState::tools
    std::optional<ToolState> before;  // pose consumed at the previous step
    std::optional<ToolState> stroke;  // pose where the current stationary closing stroke began
  };
  std::vector<Scissors> m_scissors;
  cutting::CutOptions m_cut_options;
  CutMethod m_method = CutMethod::kPattern;  // the scene's [cutting] method
  CuttingStageOptions m_options;
  std::unique_ptr<cutting::TetBvh> m_bvh;
  std::uint64_t m_bvh_version = 0;
  std::uint64_t m_bvh_step = ~0ull;
  cutting::SweepWarnings m_sweep_warnings;
  CuttingStageStats m_stats;
};

}  // namespace serosa::cutting
