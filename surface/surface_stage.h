// The "surface" stage: keeps the organs' boundary surface (surface/extract_surface.h) in step with
// the mesh, in SimState::shared.surface, where contact, rendering and pictures read it. Its wound
// flags (face_cut) are taken against the uncut boundary of the scene's initial mesh
// (surface/cut_faces.h), so the renderer can draw wounds from it as it is. The cut of
// the step (SimState::events.cuts) updates it incrementally (surface/update_surface.h); it is
// extracted anew only on the first step and when it cannot follow the cuts (a step with several
// cuts, whose deltas each describe the mesh between two of them: update_surface needs the mesh
// right after its delta).
#pragma once

#include <cstdint>
#include <string_view>

#include "engine/stage.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "surface/cut_faces.h"
#include "surface/extract_surface.h"
#include "surface/surface_mesh.h"
#include "surface/update_surface.h"

namespace serosa::surface {

struct SurfaceStageStats {
  std::uint64_t rebuilds = 0;        ///< full extractions (the first step, or a missed change)
  std::uint64_t updates = 0;         ///< incremental updates from deltas
  std::uint64_t failed_updates = 0;  ///< deltas update_surface refused (then rebuilt)
};

class SurfaceStage final : public Stage {
 public:
  /// `initial`: the scene's mesh before any cut (its boundary is the wound reference). Full
  /// extractions run on the GPU when CUDA is built and a device is present (the same faces in the
  /// same order as on the CPU), else on the CPU.
  explicit SurfaceStage(const TetMesh& initial);

  [[nodiscard]] std::string_view name() const noexcept override { return "surface"; }
  /// Follows the step's cut (incremental) or extracts anew; nothing when the topology is as
  /// before.
  void step(const StepContext& ctx, SimState& state) override;

  [[nodiscard]] const SurfaceStageStats& stats() const noexcept { return m_stats; }
  /// Where full extractions run.
  [[nodiscard]] surface::Backend backend() const noexcept { return m_backend; }

 private:
  void rebuild(SimState& state);

  surface::Backend m_backend;
  surface::OriginalSurface m_original;  // the uncut boundary, in rest coordinates
  surface::FaceTable m_table;  // faces of shared.surface by their tet face (update_surface)
  bool m_built = false;
  SurfaceStageStats m_stats;
};

}  // namespace serosa::surface
