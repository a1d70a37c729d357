// DrawnSurface: the surface the window and the pictures draw for a state. It is the surface
// stage's (SimState::shared.surface, kept incrementally with its wound flags) whenever that is
// current; only a scene without a surface stage gets one extracted here, once per topology change,
// against the uncut boundary of the initial mesh.
#pragma once

#include <cstdint>

#include "engine/sim_state.h"
#include "surface/cut_faces.h"
#include "surface/surface_mesh.h"

namespace serosa::app {

class DrawnSurface {
 public:
  /// `initial`: the scene's mesh before any cut (the wound reference).
  explicit DrawnSurface(const TetMesh& initial);

  /// The surface of `state`, valid until the next call.
  [[nodiscard]] const SurfaceMesh& of(const SimState& state);

 private:
  surface::OriginalSurface m_original;
  SurfaceMesh m_own;
  bool m_have_own = false;
};

}  // namespace serosa::app
