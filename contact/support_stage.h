// The "supports" stage (contact slot, after the tools touched): the organs rest on the planes the
// scene lists (Scene::supports: the posterior abdominal wall), so gravity can be on without the
// bowel dropping away from the instruments.
//
// A free node below a plane is pushed back along its normal by a penalty force, k * depth, with k
// capped at kSupportBeta * m / dt^2 as the tools' contact is (contact/tool_contact_stage.h) so the
// explicit force cannot overshoot the implicit step, and its velocity into or out of the plane is
// damped by kSupportDamping * m / dt so a node settles instead of bouncing. A node resting on a
// plane under its own weight sinks g dt^2 / kSupportBeta into it (0.25 mm at 200 Hz), more under
// the tissue above it (1.5 mm under a 1 cm beam, tests/app/test_supports.cpp). The planes do not
// hold the tissue sideways (no friction): what keeps an organ in place is its attachments (the
// scene's fixed nodes).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/stage.h"

namespace serosa::contact {

inline constexpr double kSupportStiffness = 200.0;  ///< N/m per node (as the tools' contact)
inline constexpr double kSupportBeta = 1.0;         ///< stiffness cap: beta m / dt^2
inline constexpr double kSupportDamping = 0.5;      ///< normal damping: this times m / dt

class SupportStage final : public Stage {
 public:
  /// `owns_forces`: no contact stage writes SimState::events.external_force_n before this one,
  /// so it starts each step's forces itself (else it adds to the contact stage's).
  SupportStage(const Scene& scene, bool owns_forces);

  [[nodiscard]] std::string_view name() const noexcept override { return "supports"; }
  void step(const StepContext& ctx, SimState& state) override;

  /// Nodes the planes pushed in the last step.
  [[nodiscard]] std::int64_t contacts() const noexcept { return m_contacts; }

 private:
  std::vector<Support> m_supports;
  bool m_owns_forces = false;
  std::int64_t m_contacts = 0;
};

}  // namespace serosa::contact
