#include "engine/live_pose_stage.h"

#include "engine/sim_state.h"

namespace serosa {

void LivePoseStage::step(const StepContext& /*ctx*/, SimState& state) {
  for (const Source& s : m_sources) {
    if (s.pose == nullptr || s.tool >= state.tools.size()) continue;
    const ToolState t = s.pose->load();
    if (t.tick > 0) state.tools[s.tool] = t;
  }
}

}  // namespace serosa
