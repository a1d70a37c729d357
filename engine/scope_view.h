// What an endoscope sees. Its optic looks along the shaft (the 0 degree optic) or kScopeAngleDeg
// off it, towards the image's down side (the 30 degree optic, chosen by the kScopeAngledButton
// bit of its input: the trainee's O key, or a script's buttons column), over a field
// kScopeFovDeg wide. The window draws the same view (render::endoscope_camera); the metrics take
// a tool as seen while its tip lies within the circle the field's height spans (a laparoscope's
// picture is round), so a tip in a corner of a wide window already counts as out of view.
#pragma once

#include <cstdint>

#include "engine/math.h"
#include "engine/tool_state.h"

namespace serosa {

/// An endoscope input's buttons bit: the 30 degree optic (else the 0 degree one).
inline constexpr std::uint32_t kScopeAngledButton = 1u << 0;
/// The angled optic's view off the shaft, degrees.
inline constexpr double kScopeAngleDeg = 30.0;
/// The field of view (the picture's height), degrees.
inline constexpr double kScopeFovDeg = 70.0;

struct ScopeView {
  Vec3 eye = Vec3::Zero();      ///< the scope's tip, m (world)
  Vec3 dir = Vec3::UnitZ();     ///< unit viewing direction
  Vec3 up = Vec3::UnitY();      ///< unit up of the picture
  double half_angle_rad = 0.0;  ///< half the field of view
};

/// The optic's angle off the shaft for the scope's input, degrees (0 or kScopeAngleDeg).
[[nodiscard]] double scope_angle_deg(const ToolState& scope);
/// Whether a device has posed the scope (its input is not the default: tip at the origin,
/// identity rotation); an unposed scope sees nothing.
[[nodiscard]] bool scope_posed(const ToolState& scope);
/// The view of the scope posed by `scope`.
[[nodiscard]] ScopeView scope_view(const ToolState& scope);
/// Whether `p` (m, world) lies in the view's round field, in front of the scope.
[[nodiscard]] bool in_view(const ScopeView& view, const Vec3& p);

}  // namespace serosa
