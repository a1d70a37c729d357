// The organs' surroundings a scene asks for ([render] surroundings), as the renderer's plain
// Scenery: built once per scene and handed to every frame (app/frame_pictures.h, app/session.h).
#pragma once

#include "engine/scene/scene.h"
#include "engine/tet_mesh.h"
#include "render/render_frame.h"

namespace serosa::app {

/// With `surroundings = "abdomen"`: render::make_abdomen (render/scenery.h) on the scene's first
/// [[support]] plane, around the bounding box of `mesh`'s rest positions (the assembled organs),
/// laid out with the scene's "up" (against gravity) in the plane. Empty (no scenery) with
/// "none", without a support, or for a mesh with no nodes.
[[nodiscard]] render::Scenery scenery_from_scene(const Scene& scene, const TetMesh& mesh);

}  // namespace serosa::app
