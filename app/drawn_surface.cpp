#include "app/drawn_surface.h"

#include "surface/extract_surface.h"

namespace serosa::app {

DrawnSurface::DrawnSurface(const TetMesh& initial)
    : m_original(initial, surface::extract_surface(initial)) {}

const SurfaceMesh& DrawnSurface::of(const SimState& state) {
  const SurfaceMesh& kept = state.shared.surface;
  if (!kept.faces.empty() && kept.topology_version == state.mesh.topology_version) return kept;
  if (!m_have_own || m_own.topology_version != state.mesh.topology_version) {
    m_own = surface::extract_surface(state.mesh, m_original);
    m_have_own = true;
  }
  return m_own;
}

}  // namespace serosa::app
