// ScopeControl: the endoscope in the trainee's hands (the session's window thread). The scope
// pivots about its trocar like any laparoscopic instrument (haptics/trocar_kinematics.h):
// dragging with the right mouse button pitches and yaws it, I and K insert and retract it, comma
// and period rotate it about its axis, which with the 30 degree optic (O) sweeps the view around.
// The optic is part of the pose (engine/scope_view.h): the recording keeps it, and the metrics
// judge what the trainee saw.
// It starts at the scene script's first pose; each change is published as the scope's ToolState
// through a Seqlock that the solver's LivePoseStage (engine/live_pose_stage.h) takes at its next
// step, so the recording holds what the solver consumed and replays without the window.
#pragma once

#include <cstdint>

#include "engine/scene/scene.h"
#include "engine/seqlock.h"
#include "engine/tool_state.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::render {
class Window;
}

namespace serosa::window {

struct ScopeMapping {
  double rad_per_px = 0.002;   ///< pitch and yaw per pixel of right-button drag
  double m_per_press = 0.005;  ///< insertion per I or K
  double rad_per_press = 0.2;  ///< rotation per comma or period
  double max_pitch_rad = 1.2;  ///< away from the trocar's axis
};

class ScopeControl {
 public:
  /// The scope `tool` starting at `start` (its script's first pose). Its trocar is the tool's
  /// `trocar` (else 10 cm back along the shaft), the start orientation its zero angles.
  ScopeControl(const Tool& tool, const ToolState& start, const ScopeMapping& mapping = {});

  /// Reads the window's keys and right-button drag; publishes the pose when it changed.
  void update(render::Window& window);
  /// Moves the scope by joint increments (rad, rad, m, rad) and publishes the pose.
  void move(double d_pitch, double d_yaw, double d_insertion, double d_roll);
  /// Swaps the 0 and the 30 degree optic (the pose's kScopeAngledButton) and publishes the pose.
  void toggle_optic();

  /// The channel the solver reads: the start pose, then every change.
  [[nodiscard]] const Seqlock<ToolState>& pose() const noexcept { return m_pose; }
  [[nodiscard]] const haptics::Trocar& trocar() const noexcept { return m_trocar; }
  [[nodiscard]] const haptics::JointState& joints() const noexcept { return m_joints; }

 private:
  ScopeMapping m_map;
  haptics::Trocar m_trocar;
  haptics::JointState m_joints;
  Seqlock<ToolState> m_pose;
  std::uint64_t m_changes = 0;
  std::uint32_t m_buttons = 0;  // kScopeAngledButton: the 30 degree optic is in
  bool m_dragging = false;
  float m_x = 0.0f;
  float m_y = 0.0f;
};

}  // namespace serosa::window
