// An endoscopic linear cutter-stapler: two 35 mm jaws, a cartridge and an anvil, hinged at the
// tool frame's hinge (engine/tool_geometry.h: kJawLength behind the tool's tip on the shaft axis,
// where every instrument's jaws pivot; the stapler's jaws reach on beyond its tip). Closing them
// on tissue fires it: two staple lines, one each side of the knife, clamp the tissue
// (contact/clip_stage.h: each line is a ligature, Clip::Kind::kStaple), and the knife divides the
// tissue between them (cutting/cutting_stage.h: one planar cut in the jaws' closing plane).
//
// Firing: the jaw channel (the scripts' jaw column, the mouse's J key, the rig's jaw) is the
// trigger, as for the clip applier: jaws opened to kStaplerArmRad or wider fire when they close
// to kStaplerFireRad, once per closure. The jaws must open again before the next fire. So every
// device fires it the same way and no button is taken.
//
// The stapler's frame (StaplerJaws::frame) has the clip's columns: across (the tool's local +x:
// the jaws close along it and press the tissue across it), pin (local +y, the hinge pin: the
// staple lines lie kStapleLineOffset either side of the knife along it) and along (local +z, the
// shaft direction, from the hinge along the jaws). The knife runs in the jaws' closing plane
// (pin = 0) from kStapleStart to kCartridgeLength beyond the hinge, across the wedge the jaws
// closed from.
#pragma once

#include <array>
#include <optional>

#include "engine/math.h"
#include "engine/tool_state.h"

namespace serosa {

/// The cartridge's stapled length, m: each jaw is this long, hinge to tip (an endoscopic linear
/// cutter's cartridges are 30, 45 or 60 mm; 35 mm suits a 7 mm appendix base, with room).
inline constexpr double kCartridgeLength = 0.035;
/// The staple lines and the knife start this far beyond the hinge, m.
inline constexpr double kStapleStart = 0.003;
/// Each staple line's centre lies this far from the knife, either side along the pin, m.
inline constexpr double kStapleLineOffset = 0.002;
/// Half the width of one staple line (three staggered rows), along the pin, m.
inline constexpr double kStapleLineHalfWidth = 0.001;
/// A closed staple's height, m: the stapled tissue is pressed to this across the jaws.
inline constexpr double kStapleGap = 1.5e-3;
/// Jaws opened this wide (rad) arm the stapler ...
inline constexpr double kStaplerArmRad = 0.2;
/// ... and fire when they then close to this, rad (fully closed, to a rig's reading).
inline constexpr double kStaplerFireRad = 0.02;

/// Follows one stapler's jaw channel: fires once per closure from an armed opening.
struct StaplerTrigger {
  double widest_rad = 0.0;  ///< the widest opening since the last fire, rad
  template <class S, class F>
  static void each(S& s, F&& f) {
    f(s.widest_rad);
  }

  /// Takes this step's jaw angle (rad); returns the opening the jaws fired from when they fire
  /// now, else std::nullopt.
  [[nodiscard]] std::optional<double> update(double jaw_rad);
};

/// A stapler's jaws where they fire: the hinge and frame of its pose, and the opening they closed
/// from (the wedge the tissue between them lay in).
struct StaplerJaws {
  Vec3 hinge = Vec3::Zero();      ///< m
  Mat3 frame = Mat3::Identity();  ///< columns: across, pin, along (orthonormal)
  double opening_rad = 0.0;       ///< full angle between the jaws they closed from, rad
};

[[nodiscard]] StaplerJaws stapler_jaws(const ToolState& tool, double opening_rad);

/// p in the jaws' frame: (across, pin, along) from the hinge, m.
[[nodiscard]] Vec3 stapler_local(const StaplerJaws& jaws, const Vec3& p);

/// Whether a point at `local` (stapler_local) lay between the jaws they closed from, over the
/// stapled length: along in [kStapleStart, kCartridgeLength], |across| <= along tan(opening/2).
[[nodiscard]] bool in_stapled_wedge(const StaplerJaws& jaws, const Vec3& local);

/// Which staple line a point at `local` falls in: 0 (pin < 0), 1 (pin > 0) or -1 (neither: the
/// knife's strip between them or outside), by its pin coordinate alone.
[[nodiscard]] int staple_line_of(const Vec3& local);

/// Centre of staple line k's hinge end (the jaw hinge moved kStapleLineOffset along -pin for
/// k = 0, +pin for k = 1), m.
[[nodiscard]] Vec3 staple_line_hinge(const StaplerJaws& jaws, int k);

/// The knife's path: a trapezoid in the closing plane (pin = 0), from kStapleStart to
/// kCartridgeLength along the jaws, across the wedge they closed from; corners in order, m.
[[nodiscard]] std::array<Vec3, 4> knife_polygon(const StaplerJaws& jaws);

/// Whether segment [a, b] (m) comes within r (m) of the stapled region: the wedge over the
/// stapled length, out to both staple lines' outer edges along the pin. A ligature whose centre
/// line does is in the jaws (the staples and the knife would meet it).
[[nodiscard]] bool segment_meets_stapled_region(const StaplerJaws& jaws, const Vec3& a,
                                                const Vec3& b, double r);

}  // namespace serosa
