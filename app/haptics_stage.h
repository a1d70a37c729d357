// The "haptics" effect in a headless run: the 1 kHz haptic loop (haptics/haptic_loop.h) runs on
// its own thread beside the solver, driving a ScriptDevice that plays the scene's scripted tool
// path in real time (the regression run of the whole device path, without a rig). Hand-offs
// (shared/DESIGN.md "Threads and hand-offs"), both through engine/seqlock.h:
//   loop -> solver: each handle's ToolState, written every tick; this stage (right after the
//     "tools" stage) takes the newest one at the step boundary and puts it into SimState::tools,
//     so the record stage records exactly what the solver consumed and a replay reproduces the
//     run bit for bit without the loop;
//   solver -> loop: a ContactModel (step, time, each handle's simulated tip), published each step.
// Handles: the first two scripted tools that are not endoscopes (scene order) take handles 0 and
// 1; they must share one script file. Each handle's trocar is its tool's `trocar` (its axis
// pointing at the tool's first scripted tip), or the first tip itself when none is given.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "engine/scene.h"
#include "engine/stage.h"
#include "haptics/contact_model.h"

namespace serosa::haptics {
class HapticLoop;
class ScriptDevice;
}  // namespace serosa::haptics

namespace serosa::app {

class HapticsStage final : public Stage {
 public:
  /// Throws InputError when no scripted tool can take a handle, or the handle tools' scripts
  /// differ. The loop starts at the first step.
  explicit HapticsStage(const Scene& scene);
  ~HapticsStage() override;

  [[nodiscard]] std::string_view name() const noexcept override { return "haptics"; }
  void step(const StepContext& ctx, SimState& state) override;

  /// Stops the loop (idempotent); telemetry is final afterwards.
  void stop();
  /// The loop's telemetry (LoopTelemetry::write_json) as JSON; stops the loop first.
  [[nodiscard]] nlohmann::json telemetry_json();
  /// Scene tool index of each handle (nullopt: idle handle).
  [[nodiscard]] const std::array<std::optional<std::size_t>, haptics::kHandles>& handle_tools()
      const noexcept {
    return m_tool;
  }

 private:
  std::array<std::optional<std::size_t>, haptics::kHandles> m_tool{};
  haptics::ContactModelChannel m_model;
  std::unique_ptr<haptics::ScriptDevice> m_device;
  std::unique_ptr<haptics::HapticLoop> m_loop;
  bool m_started = false;
};

}  // namespace serosa::app
