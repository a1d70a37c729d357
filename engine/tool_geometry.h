// Where a laparoscopic instrument's parts are, given the ToolState the solver consumed.
//
// Convention (scripted paths, rig and recordings alike): the tool's orientation maps its local
// frame to the scene frame; local +z is the shaft direction, from the trocar into the body; the
// jaws open in the local x-z plane about a hinge pin along local y. ToolState::tip_m is the
// distal tip of the closed jaws; the hinge sits kJawLength behind it on the shaft axis. Jaw k
// (0: towards local +x, 1: towards -x) points at angle +-jaw_rad/2 from the shaft axis, so
// jaw_rad is the full opening angle between the jaws.
#pragma once

#include <array>

#include "engine/math.h"
#include "engine/tool_state.h"

namespace serosa {

/// Length of each jaw (scissor blade or grasper jaw), hinge to tip, m.
inline constexpr double kJawLength = 0.015;
/// Shaft radius (5 mm instruments), m.
inline constexpr double kShaftRadius = 0.0025;

/// A tool's frame in the scene frame.
struct ToolFrame {
  Vec3 tip = Vec3::Zero();       ///< distal tip of the closed jaws, m
  Vec3 hinge = Vec3::Zero();     ///< jaw hinge, m
  Vec3 forward = Vec3::UnitZ();  ///< unit shaft direction (local +z), into the body
  Vec3 side = Vec3::UnitX();     ///< unit local +x: jaw 0 opens towards it
  Vec3 pin = Vec3::UnitY();      ///< unit local +y: the hinge pin, normal of the jaw plane
};

/// The frame of `tool` (quaternion normalized here; a zero quaternion is the identity).
[[nodiscard]] ToolFrame tool_frame(const ToolState& tool, double jaw_length_m = kJawLength);

/// Tip of jaw k (0 or 1), m: hinge + L (cos(a) forward +- sin(a) side), a = jaw_rad / 2.
[[nodiscard]] Vec3 jaw_tip(const ToolFrame& frame, double jaw_rad, int k,
                           double jaw_length_m = kJawLength);

/// Whether p lies between the open jaws: within the wedge the two jaws span about the hinge (out
/// to jaw_length_m), no farther than half_thickness_m from the jaw plane, m.
[[nodiscard]] bool between_jaws(const ToolFrame& frame, double jaw_rad, const Vec3& p,
                                double half_thickness_m, double jaw_length_m = kJawLength);

/// Distance from p to segment [a, b], m.
[[nodiscard]] double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace serosa
