// ContactModel: what the solver publishes (through a Seqlock, at its own rate) for the 1 kHz loop
// to render: per tool the simulated tool tip for the virtual coupling, up to kMaxContacts local
// contact planes (point, normal, stiffness), the pull of grasped tissue and the torque of tissue
// between closing blades. Plain fixed-size data: no pointers, no allocation.
#pragma once

#include <array>
#include <cstdint>
#include <type_traits>

#include "engine/contact_plane.h"
#include "engine/seqlock.h"
#include "haptics/rig_protocol.h"

namespace serosa::haptics {

inline constexpr std::size_t kMaxContacts = 4;

using serosa::ContactPlane;  // engine/contact_plane.h: the contact stage hands it over

/// One tool's part of the model.
struct ToolContact {
  std::array<double, 3> sim_tip_m{0.0, 0.0, 0.0};  ///< the solver's simulated tool tip, m
  std::uint32_t coupled = 0;                       ///< 1: render the virtual coupling to sim_tip_m
  std::uint32_t n_contacts = 0;                    ///< valid entries of contacts (<= kMaxContacts)
  std::array<ContactPlane, kMaxContacts> contacts{};
  std::array<double, 3> held_pull_N{0.0, 0.0, 0.0};  ///< grasped tissue's pull on the jaws, N
  double jaw_torque_Nm = 0.0;  ///< tissue between closing blades, N m (+ opens the jaws)
  /// The tissue's push on the shaft as the tip force with the same effect at the port's joints
  /// (its lateral part times the lever of where it acts, its axial part as it is), N.
  std::array<double, 3> shaft_push_N{0.0, 0.0, 0.0};
};

/// The whole model, one per solver step.
struct ContactModel {
  std::uint64_t step = 0;  ///< solver step that produced it; 0 = no model yet (zero force)
  double time_s = 0.0;     ///< simulation time, s
  double coupling_stiffness_Npm = 300.0;  ///< virtual coupling spring, N/m (>= 0)
  std::array<ToolContact, kHandles> tools{};
  std::uint32_t cut_events = 0;      ///< cumulative number of cuts applied so far
  std::uint32_t contact_events = 0;  ///< cumulative number of contact set changes so far
};
static_assert(std::is_trivially_copyable_v<ContactModel>);

/// The hand-off the solver writes and the loop reads (single writer, lock-free reader).
using ContactModelChannel = Seqlock<ContactModel>;

}  // namespace serosa::haptics
