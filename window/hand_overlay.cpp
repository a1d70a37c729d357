#include "window/hand_overlay.h"

#include <algorithm>

#include "engine/hook.h"
#include "engine/instrument_hold.h"
#include "engine/jaw_range.h"

namespace serosa::window {

std::vector<render::OverlayHand> overlay_hands(const Scene& scene, const SimState& state,
                                               const HandleTools& handles,
                                               std::size_t active_handle,
                                               const render::RenderFrame& frame) {
  std::vector<render::OverlayHand> out;
  for (std::size_t h = 0; h < handles.size(); ++h) {
    if (!handles[h] || *handles[h] >= scene.tools.size() || *handles[h] >= state.tools.size())
      continue;
    const std::size_t i = *handles[h];
    const Tool& tool = scene.tools[i];
    render::OverlayHand o;
    o.hand = h == 0 ? "left" : "right";
    o.tool = tool.name;
    o.active = h == active_handle;
    o.jaw_rad = state.tools[i].jaw_rad;
    o.jaw_max_rad = max_jaw_rad(tool.kind);
    o.has_pedal = tool.kind == ToolKind::kHook;
    o.pedal = pedal_down(state.tools[i]);
    if (i < state.shared.grasped.size()) o.holding_nodes = state.shared.grasped[i].size();
    o.entering = in_port(state.tools[i]);
    for (const render::RenderTool& t : frame.tools) {
      if (t.scene_tool != i || !t.has_tissue) continue;
      o.has_tissue = true;
      o.tissue_distance_m = t.tissue_distance_m;
      o.tissue_in_jaws_m = t.tissue_in_jaws_m;
    }
    out.push_back(o);
  }
  return out;
}

std::vector<std::string> waiting_instruments(const Scene& scene, const SimState& state,
                                             const HandleTools& handles) {
  std::vector<std::string> out;
  for (std::size_t i = 0; i < scene.tools.size() && i < state.tools.size(); ++i) {
    const bool held = std::find(handles.begin(), handles.end(), i) != handles.end();
    if (!held && scene.tools[i].kind != ToolKind::kEndoscope && in_port(state.tools[i]))
      out.push_back(scene.tools[i].name);
  }
  return out;
}

void mark_active_tool(render::RenderFrame& frame, std::optional<std::size_t> tool) {
  for (render::RenderTool& t : frame.tools) t.active = tool && t.scene_tool == *tool;
}

}  // namespace serosa::window
