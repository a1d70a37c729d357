#include "app/surface_stage.h"

#include <stdexcept>

#include "engine/sim_state.h"
#include "surface/extract_surface.h"

namespace serosa::app {

void SurfaceStage::rebuild(const TetMesh& mesh) {
  m_surface = surface::extract_surface(mesh);
  m_table = surface::build_face_table(mesh, m_surface);
  m_built = true;
  ++m_stats.rebuilds;
}

void SurfaceStage::step(const StepContext& /*ctx*/, SimState& state) {
  if (!m_built || m_surface.topology_version != state.mesh.topology_version) rebuild(state.mesh);
}

void SurfaceStage::on_topology_change(const TetMesh& after, const TopologyDelta& delta) {
  if (!m_built) return;  // the next step builds it from scratch anyway
  try {
    surface::update_surface(m_surface, m_table, after, delta);
    ++m_stats.updates;
  } catch (const std::invalid_argument&) {
    ++m_stats.failed_updates;
    rebuild(after);
  }
}

}  // namespace serosa::app
