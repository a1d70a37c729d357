// How far each kind of instrument opens its jaws, the one range the mouse, the rig handle and the
// scripted paths share: the scripts open no instrument wider (config/paths/*.csv), and a trainee
// at the mouse opens it as wide as the script does, so that a 7 mm appendix fits between the
// scissors' 15 mm blades as it does on the rig.
#pragma once

#include "engine/scene/scene.h"

namespace serosa {

/// Full opening angle between the jaws of an instrument of `kind` opened as wide as it goes, rad
/// (0 for instruments without jaws: the hook, the endoscope).
[[nodiscard]] constexpr double max_jaw_rad(ToolKind kind) noexcept {
  switch (kind) {
    case ToolKind::kScissors:
      return 1.2;
    case ToolKind::kGrasper:
      return 1.0;
    case ToolKind::kClipApplier:
      return 0.7;
    case ToolKind::kEndoloop:
      return 0.6;
    case ToolKind::kStapler:  // 35 mm jaws: 21 mm apart at the tips, 12 mm at 20 mm
      return 0.6;
    case ToolKind::kHook:
    case ToolKind::kEndoscope:
      break;
  }
  return 0.0;
}

}  // namespace serosa
