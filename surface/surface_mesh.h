// The boundary surface type lives in engine (engine/surface_mesh.h): the surface stage hands it to
// contact and rendering through SimState. The surface domain's code names it here.
#pragma once

#include "engine/surface_mesh.h"

namespace serosa::surface {
using serosa::GroupRange;
using serosa::SurfaceMesh;
}  // namespace serosa::surface
