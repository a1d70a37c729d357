// The tissue's resistance to closing scissors, felt through the rig's jaw channel.
//
// The blades pass through the tissue without pushing it (the cutting stage cuts a whole stroke
// when it ends), so what resists is the tissue the blades have closed on and not yet cut: the
// tissue inside the wedge they swept since the stroke began (between the opening it began with
// and the current one, both sides), within the blade length. Shearing it takes a stress of
// kShearStrengthPerYoung x its Young's modulus over its area in the blades' plane, at its
// distance from the hinge:
//     torque = sum over nodes in the swept wedge  s_n * (V_n / h) * r_n        (N m, + opens)
// where V_n is the node's share of the tets' rest volume (a quarter of each tet it is in), h the
// thickness of the slab about the blades' plane the nodes are taken from (so V_n / h is the area
// a node stands for), s_n the volume-weighted strength of its tets and r_n its distance from the
// hinge; the same sum without r_n is the shear force each blade presses the tissue with (N), what
// the metrics count as the scissors' force on the tissue. The torque grows as the blades close on
// tissue and is gone once the stroke is cut (the caller starts a new stroke then): the drop a
// surgeon feels when the tissue gives way.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/tet_mesh.h"
#include "engine/tissue_stress.h"
#include "engine/tool_state.h"

namespace serosa::contact {

/// Failure shear stress over Young's modulus (soft tissue stiffens and tears at strains of
/// order one), dimensionless.
inline constexpr double kShearStrengthPerYoung = 1.0;
/// Thickness of the slab about the blades' plane whose nodes count, m (about two node spacings of
/// the organ meshes, so that a tissue crossing the plane always has nodes in it).
inline constexpr double kBladeSlab = 0.003;

/// The tissue closed on and not yet cut, as the jaws feel it.
struct BladeLoad {
  double torque_nm = 0.0;  ///< about the hinge, N m, positive opens the jaws
  /// the shear force each blade presses the tissue with, N (sum of s_n V_n / h: the torque's
  /// forces without their levers)
  double force_n = 0.0;
};

class BladeResistance {
 public:
  /// Node volumes and strengths for the mesh's current topology (call after every topology
  /// change; cheap: one pass over the tets).
  void update(const TetMesh& mesh, const LameTable& table);
  [[nodiscard]] std::uint64_t topology_version() const noexcept { return m_version; }

  /// What the tissue puts on the jaws of scissors posed `tool` (current positions), whose stroke
  /// began at opening `stroke_open_rad`; zero when they are not closing (jaw_rad >=
  /// stroke_open_rad).
  [[nodiscard]] BladeLoad load(const TetMesh& mesh, const ToolState& tool,
                               double stroke_open_rad) const;

 private:
  std::uint64_t m_version = ~0ull;
  std::vector<double> m_volume_m3;    // (n) node's share of rest volume
  std::vector<double> m_strength_pa;  // (n) shear strength of the tissue around it
};

}  // namespace serosa::contact
