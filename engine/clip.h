// A ligature: a titanium clip a clip applier closes across tissue (a vessel, the mesoappendix), an
// endoloop's suture cinched around it (the appendix's base), or one of the two staple lines a
// cutter-stapler lays either side of its knife (engine/stapler.h). It clamps the tissue it closes
// on and is carried by that tissue from then on (contact/clip_stage.h); closing scissors never cut
// through one (cutting/cutting_stage.h), and the renderer draws it. Placed ligatures are part of
// the step's hand-off, for those readers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/math.h"
#include "engine/stapler.h"

namespace serosa {

/// Where a clip sits in an applier's jaws: from this far beyond the jaw hinge, m ...
inline constexpr double kClipStart = 0.005;
/// ... over this length along the jaws, m (a medium-large clip, 9 mm legs).
inline constexpr double kClipLength = 0.009;
/// Half the width of a clip's legs along the hinge pin, m.
inline constexpr double kClipHalfWidth = 0.001;
/// What is left between a closed clip's legs, m: the clamped tissue is pressed to this.
inline constexpr double kClipGap = 5e-4;

/// Half the width of an endoloop's cinched suture along its axis (the knot's bite), m.
inline constexpr double kLoopHalfWidth = 0.0015;
/// What is left inside a cinched loop, m: the tissue it encircles is pressed within this radius.
inline constexpr double kLoopTightRadius = 0.001;

/// One placed ligature, in the scene frame, where the tissue carries it now.
struct Clip {
  enum class Kind : std::uint8_t {
    kClip,  ///< a clip: two legs over [kClipStart, kClipStart + kClipLength] beyond the hinge
    kLoop,  ///< a cinched endoloop: a ring of radius kLoopTightRadius about its centre
    /// a staple line: rows of staples over [kStapleStart, kCartridgeLength] beyond the stapler's
    /// hinge, kStapleLineHalfWidth either side of its centre line along the pin
    kStaple,
  };
  Kind kind = Kind::kClip;
  /// A clip: the applier's jaw hinge when it closed; a loop: the ring's centre; a staple line: the
  /// stapler's hinge moved to the line's centre along the pin; carried along, m.
  Vec3 hinge_m = Vec3::Zero();
  /// A clip's (and a staple line's) columns: across (the direction its legs pressed the tissue),
  /// pin (its width) and along (its length, away from the hinge). A loop's: two directions in its
  /// plane and its axis. Orthonormal, right-handed.
  Mat3 frame = Mat3::Identity();
  std::size_t tool = 0;     ///< the applier that placed it (index into Scene::tools)
  double placed_s = 0.0;    ///< simulated time it closed, s
  std::vector<int> groups;  ///< groups of the tets around the nodes it clamps (sorted, unique)
  std::size_t nodes = 0;    ///< nodes it clamps
  std::int32_t node = -1;   ///< one of them (the first), id: which piece it is on after a cut
  Vec3 rest_centre_m = Vec3::Zero();  ///< the mean rest position of the nodes it clamps, m

  /// End k of a clip's (a staple line's) centre line (0: nearer the hinge, 1: the far end), m; of
  /// a loop's axis across its suture (kLoopHalfWidth either side of its centre).
  [[nodiscard]] Vec3 end(int k) const {
    if (kind == Kind::kLoop) return hinge_m + (k == 0 ? -1.0 : 1.0) * kLoopHalfWidth * axis();
    if (kind == Kind::kStaple) return hinge_m + (k == 0 ? kStapleStart : kCartridgeLength) * axis();
    return hinge_m + (kClipStart + (k == 0 ? 0.0 : kClipLength)) * axis();
  }
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.kind), f(s.hinge_m), f(s.frame), f(s.tool), f(s.placed_s), f(s.groups), f(s.nodes),
        f(s.node), f(s.rest_centre_m);
  }
  /// Unit: a clip's length, away from its hinge; a loop's axis.
  [[nodiscard]] Vec3 axis() const { return frame.col(2); }
  /// How far beyond its centre line a ligature reaches, m: a clip's legs' half width, a loop's
  /// cinched radius, a staple line's half width.
  [[nodiscard]] double reach_m() const {
    return kind == Kind::kLoop     ? kLoopTightRadius
           : kind == Kind::kStaple ? kStapleLineHalfWidth
                                   : kClipHalfWidth;
  }
};

}  // namespace serosa
