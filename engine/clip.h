// A ligation clip: a titanium clip a clip applier closes across tissue (a vessel, the
// mesoappendix). It clamps the tissue between its legs and is carried by that tissue from then
// on (contact/clip_stage.h); closing scissors never cut through one (cutting/cutting_stage.h),
// and the renderer draws it. Placed clips are part of the step's hand-off, for those readers.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/math.h"

namespace serosa {

/// Where a clip sits in an applier's jaws: from this far beyond the jaw hinge, m ...
inline constexpr double kClipStart = 0.005;
/// ... over this length along the jaws, m (a medium-large clip, 9 mm legs).
inline constexpr double kClipLength = 0.009;
/// Half the width of a clip's legs along the hinge pin, m.
inline constexpr double kClipHalfWidth = 0.001;
/// What is left between a closed clip's legs, m: the clamped tissue is pressed to this.
inline constexpr double kClipGap = 5e-4;

/// One placed clip, in the scene frame, where the tissue carries it now.
struct Clip {
  Vec3 hinge_m = Vec3::Zero();  ///< the applier's jaw hinge when it closed, carried along, m
  /// Columns: across (the direction its legs pressed the tissue), pin (its width) and along (its
  /// length, away from the hinge); orthonormal, right-handed.
  Mat3 frame = Mat3::Identity();
  std::size_t tool = 0;     ///< the applier that placed it (index into Scene::tools)
  double placed_s = 0.0;    ///< simulated time it closed, s
  std::vector<int> groups;  ///< groups of the tets around the nodes it clamps (sorted, unique)
  std::size_t nodes = 0;    ///< nodes it clamps

  /// End k of its centre line (0: nearer the hinge, 1: the far end), m.
  [[nodiscard]] Vec3 end(int k) const {
    return hinge_m + (kClipStart + (k == 0 ? 0.0 : kClipLength)) * Vec3(frame.col(2));
  }
};

}  // namespace serosa
