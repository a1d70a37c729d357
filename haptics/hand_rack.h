// The instruments the two handles take in turn. Each handle holds one instrument at a time; the
// others wait outside the body in their ports. An exchange (the handle button: the rig's, or X
// in the window) withdraws the held instrument through its trocar and gives the handle the next
// instrument waiting, in scene order after the one it held, that the other handle does not hold.
//
// Each handle has a trocar of its own (the port of the instrument it held first), in which the
// device and the haptic loop work for the whole session: its joints (pitch, yaw, roll, insertion,
// jaw) are the same whichever instrument it holds, and the instrument's pose is the handle's pose
// carried rigidly from the handle's trocar to the instrument's (forward kinematics through a
// trocar is that trocar's rigid motion applied to the joints' pose, so the mapping is exact). The
// contact model goes back the other way, so forces render through the handle's own trocar as
// they would through the instrument's.
//
// A taken instrument enters through its port: it waits there until the handle is drawn back to
// within kEntryDepthM of its trocar (a rig's handle is where the hand left it; the mouse device
// draws its handle back itself, haptics/mouse_device.h), then it follows the handle in.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "engine/math.h"
#include "engine/tool_state.h"
#include "haptics/contact_model.h"
#include "haptics/device.h"
#include "haptics/trocar_kinematics.h"

namespace serosa::haptics {

/// A taken instrument follows its handle once the handle's insertion is at most this, m.
inline constexpr double kEntryDepthM = 0.02;

/// One instrument the handles can take.
struct RackInstrument {
  std::size_t tool = 0;      ///< index into Scene::tools
  Trocar trocar;             ///< its port
  JointState rest;           ///< where it rests once inserted (the mouse device takes it there)
  double jaw_max_rad = 1.0;  ///< its jaws' range (engine/jaw_range.h), rad
};

/// The rigid motion from one trocar's frame to another's.
struct TrocarMap {
  Quat rotation = Quat::Identity();
  Vec3 from_m = Vec3::Zero();
  Vec3 to_m = Vec3::Zero();
  [[nodiscard]] Vec3 point(const Vec3& p) const { return to_m + rotation * (p - from_m); }
  [[nodiscard]] Vec3 direction(const Vec3& d) const { return rotation * d; }
  [[nodiscard]] ToolState pose(const ToolState& s) const;
  [[nodiscard]] TrocarMap inverse() const;
};

/// The map that carries poses through trocar `from` to the same joints through `to`.
[[nodiscard]] TrocarMap trocar_map(const Trocar& from, const Trocar& to);

class HandRack {
 public:
  /// `held`: which of `instruments` each handle holds first (nullopt: an idle handle); the
  /// handles' trocars are those instruments' ports.
  HandRack(std::vector<RackInstrument> instruments,
           std::array<std::optional<std::size_t>, kHandles> held);

  /// The handle's own trocar, in which its device works.
  [[nodiscard]] const Trocar& handle_trocar(std::size_t h) const { return m_handle[h]; }
  /// The instrument handle h holds (index into instruments()), if any.
  [[nodiscard]] std::optional<std::size_t> held(std::size_t h) const { return m_held[h]; }
  [[nodiscard]] const std::vector<RackInstrument>& instruments() const { return m_items; }
  /// Whether handle h's instrument waits in its port for the handle to be drawn back.
  [[nodiscard]] bool entering(std::size_t h) const { return m_entering[h]; }

  /// Handle h takes the next instrument waiting; returns it (index into instruments()), or
  /// nullopt when none waits (then nothing changes).
  std::optional<std::size_t> exchange(std::size_t h);
  /// Follows handle h's pose (its own trocar's frame): ends the entry once it is drawn back.
  void follow(std::size_t h, const ToolState& handle_pose);

  /// Handle h's pose carried to its instrument's port.
  [[nodiscard]] ToolState to_instrument(std::size_t h, const ToolState& handle_pose) const;
  /// An instrument's contact carried back to handle h's trocar.
  [[nodiscard]] ToolContact to_handle(std::size_t h, const ToolContact& c) const;

 private:
  std::vector<RackInstrument> m_items;
  std::array<std::optional<std::size_t>, kHandles> m_held{};
  std::array<Trocar, kHandles> m_handle{};
  std::array<bool, kHandles> m_entering{};
};

}  // namespace serosa::haptics
