// The "cutting" stage: scissors cut the organs along the exact path of their blades
// (shared/DESIGN.md "Cutting"). Each step, for every scissors tool whose jaws closed since the
// previous step, each blade's edge (hinge -> blade tip, app/tool_geometry.h) sweeps a convex
// polygon between its pose at the previous step and its pose now (cutting/blade_sweep.h); the
// polygon goes to cutting::cut_mesh (candidates from a TetBvh over current positions), the
// resulting TopologyDelta is applied to the mesh between FEM steps and handed to every listener
// (FEM, surface, metrics), which update themselves incrementally.
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
#include "engine/scene.h"
#include "engine/stage.h"
#include "engine/tool_state.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {
class TetBvh;
}

namespace serosa::app {

/// One cut applied to the mesh, as listeners see it.
struct CutApplied {
  std::uint64_t step = 0;                           ///< solver step during which it happened
  std::size_t tool = 0;                             ///< index into Scene::tools
  int blade = 0;                                    ///< 0 or 1 (app/tool_geometry.h)
  const cutting::ConvexPolygon* polygon = nullptr;  ///< the swept blade polygon, m
  const TopologyDelta* delta = nullptr;             ///< applied: the filled-in fields are set
  const cutting::CutStats* stats = nullptr;
  std::vector<Vec3> removed_centroids_m;   ///< (r) current centroid of each removed tet, m
  std::vector<double> removed_volumes_m3;  ///< (r) rest volume of each removed tet, m^3
};

/// Told about each cut right after it is applied to state.mesh, in registration order.
using CutListener = std::function<void(SimState&, const CutApplied&)>;

struct CuttingStageOptions {
  /// Check every cut with cutting::check_cut (costly: copies the mesh; tests turn it on).
  bool validate = false;
};

/// Totals over the stage's life.
struct CuttingStageStats {
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
  /// Cuts with every tool of kind scissors in `scene` (its [cutting] tolerance).
  explicit CuttingStage(const Scene& scene, CuttingStageOptions options = {});
  ~CuttingStage() override;

  [[nodiscard]] std::string_view name() const noexcept override { return "cutting"; }
  void step(const StepContext& ctx, SimState& state) override;

  void add_listener(CutListener listener) { m_listeners.push_back(std::move(listener)); }
  [[nodiscard]] const CuttingStageStats& stats() const noexcept { return m_stats; }
  [[nodiscard]] std::size_t num_scissors() const noexcept { return m_scissors.size(); }

 private:
  void cut(const StepContext& ctx, SimState& state, std::size_t tool, int blade,
           const cutting::ConvexPolygon& polygon);

  struct Scissors {
    std::size_t tool = 0;             // index into Scene::tools / SimState::tools
    std::optional<ToolState> before;  // pose consumed at the previous step
  };
  std::vector<Scissors> m_scissors;
  cutting::CutOptions m_cut_options;
  CuttingStageOptions m_options;
  std::unique_ptr<cutting::TetBvh> m_bvh;
  std::uint64_t m_bvh_version = 0;
  std::uint64_t m_bvh_step = ~0ull;
  cutting::SweepWarnings m_sweep_warnings;
  std::vector<CutListener> m_listeners;
  CuttingStageStats m_stats;
};

}  // namespace serosa::app
