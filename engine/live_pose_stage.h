// LivePoseStage: tools posed by a thread outside the solver (in the trainee session, the window
// moves the endoscope). At each step boundary each such tool takes the newest pose its channel
// holds (a Seqlock the other thread writes; the stage only reads), so the record stage records
// what the solver consumed and a replay needs no window. A channel nobody has written yet (tick
// 0) leaves its tool as it is.
#pragma once

#include <cstddef>
#include <string_view>
#include <vector>

#include "engine/seqlock.h"
#include "engine/stage.h"
#include "engine/tool_state.h"

namespace serosa {

class LivePoseStage final : public Stage {
 public:
  struct Source {
    std::size_t tool = 0;                      ///< index into Scene::tools
    const Seqlock<ToolState>* pose = nullptr;  ///< outlives the stage
  };
  explicit LivePoseStage(std::vector<Source> sources) : m_sources(std::move(sources)) {}

  [[nodiscard]] std::string_view name() const noexcept override { return "live_poses"; }
  void step(const StepContext& ctx, SimState& state) override;

 private:
  std::vector<Source> m_sources;
};

}  // namespace serosa
