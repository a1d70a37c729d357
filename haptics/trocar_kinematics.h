// Trocar kinematics: a laparoscopic instrument pivots about its trocar on the abdominal wall.
//
// Joint space (one handle): pitch, yaw, roll (rad), insertion (m), jaw (rad). The trocar frame
// (pivot point p, rotation R0 into the scene) is fixed per port. The tool frame is
//     R = R0 * Ry(yaw) * Rx(pitch) * Rz(roll),   shaft d = R * e_z (points into the patient),
//     tip = p + insertion * d.
// Pitch is the elevation of the shaft (|pitch| < pi/2; the representation is singular at
// +-pi/2, outside any rig's workspace), yaw the azimuth, roll the rotation about the shaft.
//
// Forces: for a force F (N, scene frame) acting on the tool tip, the joint efforts are the
// Jacobian transpose  tau = J^T F  (pitch/yaw torques in N*m about the pivot, roll torque from a
// tip moment, insertion force along d). The handle sits on the other side of the pivot at
// handle_length_m: the lateral part of F reaches the hand reversed and scaled by the lever ratio
// insertion / handle_length, the axial part unchanged, so the moment about the pivot is kept.
#pragma once

#include "engine/math.h"
#include "engine/tool_state.h"

namespace serosa::haptics {

/// One handle's joint coordinates.
struct JointState {
  double pitch_rad = 0.0;    ///< elevation of the shaft about the trocar x axis
  double yaw_rad = 0.0;      ///< azimuth about the trocar y axis
  double roll_rad = 0.0;     ///< rotation about the shaft
  double insertion_m = 0.0;  ///< tip distance beyond the pivot along the shaft (>= 0 in use)
  double jaw_rad = 0.0;      ///< jaw opening (0 = closed)
};

/// Joint-space efforts, same order as JointState.
struct JointEffort {
  double pitch_Nm = 0.0;
  double yaw_Nm = 0.0;
  double roll_Nm = 0.0;
  double insertion_N = 0.0;
  double jaw_Nm = 0.0;
};

/// A port on the abdominal wall.
struct Trocar {
  Vec3 pivot_m = Vec3::Zero();       ///< pivot point, scene frame, m
  Quat rotation = Quat::Identity();  ///< trocar frame -> scene (its +z points into the body)
  double handle_length_m = 0.25;     ///< pivot to the hand grip, outside the body, m (> 0)
};

/// Tool-frame rotation for the given joints (scene frame).
[[nodiscard]] Quat tool_rotation(const Trocar& t, const JointState& q);

/// Joints -> tool state (tip position, orientation, jaw). tick, time and buttons are left 0.
[[nodiscard]] ToolState forward(const Trocar& t, const JointState& q);

/// Tool pose -> joints (inverse of forward for |pitch| < pi/2). Insertion is the signed distance
/// of the tip along the shaft; the angles come from the orientation, so insertion 0 is regular.
[[nodiscard]] JointState inverse(const Trocar& t, const ToolState& s);

/// Tip position only -> joints, keeping `previous`'s roll and jaw. Where the tip is within
/// 1e-9 m of the pivot the direction is undefined: pitch and yaw of `previous` are kept
/// (the singular insertion 0 never produces NaN).
[[nodiscard]] JointState inverse_from_tip(const Trocar& t, const Vec3& tip_m,
                                          const JointState& previous);

/// 3x3 Jacobian d tip / d (pitch, yaw, insertion) at q, scene frame (columns in that order).
[[nodiscard]] Mat3 tip_jacobian(const Trocar& t, const JointState& q);

/// Joint efforts for a tip force F (N) and a tip moment M (N*m), scene frame, plus a jaw torque.
/// pitch/yaw/insertion = J^T F; roll = M . shaft.
[[nodiscard]] JointEffort tip_to_joint(const Trocar& t, const JointState& q, const Vec3& force_N,
                                       const Vec3& moment_Nm = Vec3::Zero(),
                                       double jaw_torque_Nm = 0.0);

/// Force felt at the hand grip (scene frame) for a tip force F: the axial part along the shaft
/// unchanged, the lateral part times -(insertion / handle_length).
[[nodiscard]] Vec3 tip_to_handle_force(const Trocar& t, const JointState& q, const Vec3& force_N);

/// Moment of a tip force about the pivot, N*m: (tip - pivot) x F.
[[nodiscard]] Vec3 pivot_moment(const Trocar& t, const JointState& q, const Vec3& force_N);

}  // namespace serosa::haptics
