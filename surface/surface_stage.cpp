#include "surface/surface_stage.h"

#include <stdexcept>

#include "engine/sim_state.h"
#include "surface/extract_surface.h"

namespace serosa::surface {

SurfaceStage::SurfaceStage(const TetMesh& initial)
    : m_backend(surface::cuda_available() ? surface::Backend::kCuda : surface::Backend::kCpu),
      m_original(initial, surface::extract_surface(initial, m_backend)) {}

void SurfaceStage::rebuild(SimState& state) {
  state.shared.surface = surface::extract_surface(state.mesh, m_original, m_backend);
  m_table = surface::build_face_table(state.mesh, state.shared.surface);
  m_built = true;
  ++m_stats.rebuilds;
}

void SurfaceStage::step(const StepContext& /*ctx*/, SimState& state) {
  surface::SurfaceMesh& s = state.shared.surface;
  const auto& cuts = state.events.cuts;
  // A state that arrives with its surface (assembled, or restored from a snapshot) keeps it: the
  // table is derived from the surface and the mesh alone.
  if (!m_built && !s.faces.empty() && s.topology_version == state.mesh.topology_version &&
      cuts.empty()) {
    m_table = surface::build_face_table(state.mesh, s);
    m_built = true;
  }
  if (m_built && cuts.size() == 1 && s.topology_version == cuts.front().delta.version_before &&
      state.mesh.topology_version == cuts.front().delta.version_after) {
    try {
      surface::update_surface(s, m_table, state.mesh, cuts.front().delta, &m_original);
      ++m_stats.updates;
    } catch (const std::invalid_argument&) {
      ++m_stats.failed_updates;
      rebuild(state);
    }
  }
  if (!m_built || s.topology_version != state.mesh.topology_version) rebuild(state);
}

}  // namespace serosa::surface
