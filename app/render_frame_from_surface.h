// Fills the renderer's plain RenderFrame from the simulation: the boundary surface (with the
// surface module's split normals and wound flags), the tet edges for the mechanical view, the
// instruments and the endoscope's camera.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/tet_mesh.h"
#include "render/render_frame.h"
#include "surface/surface_mesh.h"

namespace serosa::app {

/// Surface part of the frame. Render vertices come from surface::compute_render_vertices: normals
/// are area-weighted and split across cut edges, creases and groups, so a wound's rim is sharp.
/// With `with_edges`: pos = all TetMesh nodes (n, unlit, for the tet edges of the mechanical view)
/// followed by the render vertices; without: the render vertices only. tri indexes the render
/// vertices; tri_group and tri_cut (the wound) come from the surface (tri_cut all 0 when the
/// surface has no flags). Group names by id. Tet edges are recomputed only when the topology
/// version changed. topology_version = the surface's. The camera, tools and overlay are left.
/// With `coagulated` ((n) node marks, SimState::blocks.cutting.coagulated): faces whose three nodes
/// are marked are tri_cut 2 (a hook's wound is dry; so is a cut through coagulated tissue), and
/// material_version = `coagulated_version`. With `stain` ((n) SimState::blocks.bleeding.stain, not
/// empty): each vertex takes its node's stain of blood (frame.stain), else frame.stain is empty.
void fill_render_frame(const TetMesh& mesh, const surface::SurfaceMesh& surface,
                       const std::map<int, std::string>& group_names, bool with_edges,
                       render::RenderFrame& frame,
                       const std::vector<std::uint8_t>* coagulated = nullptr,
                       std::uint64_t coagulated_version = 0,
                       const std::vector<float>* stain = nullptr);

/// frame.taenia_centre and taenia_axis: where the cecum's taeniae run, from the centre of the
/// groups `names` draws as cecum or colon towards where the appendix meets them (the nodes both
/// share; without any, the appendix's centre), in rest coordinates; a zero axis without both.
/// Rest positions do not move and cuts only add nodes: callers set it once, like the scenery.
void fill_taenia(const TetMesh& mesh, const std::map<int, std::string>& names,
                 render::RenderFrame& frame);

/// The names the renderer picks each group's material by (render/materials.h): the tissue the
/// scene's `[render] looks` draws the group as, else the group's own name.
[[nodiscard]] std::map<int, std::string> drawn_group_names(const Scene& scene,
                                                           std::map<int, std::string> names);

/// frame.guide: the scene's planned cut ([metrics] planned_cut), drawn as a marker; without one,
/// its clip target ([metrics] clip_target) as a short pin through the tissue there, along the
/// board's normal (the first support's, else against gravity): a dot where the clip goes.
/// frame.tools: one RenderTool per scene tool of kind scissors or grasper, posed by its latest
/// consumed input (state.tools, scene order), with the scene's trocar when given. Endoscopes are
/// cameras, not drawn; a tool no device has posed yet (tip at the origin, identity rotation: the
/// default input) is not drawn either.
void fill_render_tools(const Scene& scene, const SimState& state, render::RenderFrame& frame);

/// The camera of the scene's first endoscope tool, posed by its latest input, with the optic its
/// input chose (engine/scope_view.h), or nullopt when the scene has no endoscope or no device has
/// posed it yet (its input still the default: tip at the origin, identity rotation, or at its
/// trocar with the identity rotation, where the scene's start leaves it).
[[nodiscard]] std::optional<render::Camera> endoscope_view(const Scene& scene,
                                                           const SimState& state);

}  // namespace serosa::app
