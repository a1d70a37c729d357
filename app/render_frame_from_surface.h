// Fills the renderer's plain RenderFrame from the mechanical mesh and its boundary surface: the
// surface references mechanical node ids, so positions come straight from TetMesh::x.
#pragma once

#include <map>
#include <string>

#include "engine/tet_mesh.h"
#include "render/render_frame.h"
#include "surface/surface_mesh.h"

namespace serosa::app {

/// pos = all nodes' current positions (float, m); tri, tri_group from the surface; tri_cut all 0
/// until the surface flags cut faces; normals area-weighted; group names by id; tet edges for the
/// mechanical view when `with_edges` (recomputed only when the topology version changed). The
/// camera is left for the caller (or auto_camera).
void fill_render_frame(const TetMesh& mesh, const surface::SurfaceMesh& surface,
                       const std::map<int, std::string>& group_names, bool with_edges,
                       render::RenderFrame& frame);

}  // namespace serosa::app
