// The "surface" stage: keeps the organs' boundary surface (surface/extract_surface.h) in step with
// the mesh. A cut hands it the TopologyDelta (on_topology_change) and it updates incrementally
// (surface/update_surface.h); its step only rebuilds when it missed a change (never in a normal
// run: tests check updates > 0 and rebuilds == 1 after cuts).
#pragma once

#include <cstdint>
#include <string_view>

#include "engine/stage.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "surface/surface_mesh.h"
#include "surface/update_surface.h"

namespace serosa::app {

struct SurfaceStageStats {
  std::uint64_t rebuilds = 0;        ///< full extractions (the first step, or a missed change)
  std::uint64_t updates = 0;         ///< incremental updates from deltas
  std::uint64_t failed_updates = 0;  ///< deltas update_surface refused (then rebuilt)
};

class SurfaceStage final : public Stage {
 public:
  SurfaceStage() = default;

  [[nodiscard]] std::string_view name() const noexcept override { return "surface"; }
  /// Rebuilds when the surface does not match the mesh's topology version; else nothing.
  void step(const StepContext& ctx, SimState& state) override;
  /// Updates the surface for `delta`, already applied to `after`.
  void on_topology_change(const TetMesh& after, const TopologyDelta& delta);

  /// The boundary surface (face node ids index the mesh's nodes). Empty before the first step.
  [[nodiscard]] const surface::SurfaceMesh& surface() const noexcept { return m_surface; }
  [[nodiscard]] const SurfaceStageStats& stats() const noexcept { return m_stats; }

 private:
  void rebuild(const TetMesh& mesh);

  surface::SurfaceMesh m_surface;
  surface::FaceTable m_table;
  bool m_built = false;
  SurfaceStageStats m_stats;
};

}  // namespace serosa::app
