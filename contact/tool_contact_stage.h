// The "contact" stage (before FEM): what the tools do to the tissue by touching it.
//
// - Contact: each tool's shaft (trocar -> jaw hinge, or 10 cm back along the shaft without a
//   trocar; radius kShaftRadius) and, for a grasper that holds nothing, its jaws (hinge -> jaw
//   tips, radius kJawRadius) are capsules; a surface node inside one is pushed out along the
//   shortest way by a penalty force k * depth, capped at beta * m / dt^2 * depth so that the
//   explicit force cannot overshoot the implicit step. Forces go to FEM as external forces.
//   Scissor blades do not push: closing, they cut (cutting stage); nor do a clip applier's jaws:
//   its clip takes what lies between them (contact/clip_stage.h).
// - Grasping: when a grasper's jaws close past kGraspCloseRad, the surface nodes between its jaws
//   (inside the wedge of its widest opening since it last let go, within kGraspHalfWidth of the
//   jaw plane) are grabbed: held to the jaws through an infinitely stiff spring (Dirichlet nodes
//   that move with the tool). Opening past kGraspCloseRad + kGraspHysteresisRad lets go and
//   restores their original Dirichlet flags. The grasp force is the tissue's elastic pull on the
//   grabbed nodes (engine/tissue_stress.h).
// Each tool's total force on the tissue (N) is handed on (SimState::events.tool_force_n) for
// metrics and the haptic model; the node forces go to FEM (events.external_force_n).
// - Reactions (with the haptic planes): what each tool feels besides its tip's contact plane,
//   handed on in SimState::events.tool_reactions: a grasper's held tissue's pull (the elastic
//   force on its held nodes), the tissue's push on the shaft and where along it (the shaft
//   capsule's contact forces, reversed), and the torque of the tissue between closing scissor
//   blades (contact/blade_resistance.h; a stroke begins at the widest opening and ends with its
//   cut).
// - Haptic contact planes (on when the haptic loop is built): after the
//   forces, per tool the organ surface point nearest its tip within kHapticRange (collision BVH,
//   engine/geometry/surface_bvh.h, rebuilt on topology changes and refitted every step) with its
//   face's outward normal and kHapticStiffness: the local contact plane the 1 kHz loop renders
//   (haptics/contact_model.h), handed on in SimState::events.contact_planes. A tip pressed into
//   the tissue is below that plane and feels a force along the outward normal, opposing the
//   penetration. The same query out to kCueRange gives each tool's nearest tissue for the
//   picture's depth cue (SimState::events.tissue_near): a plane that far from the tip would
//   stand for the wrong part of a curved organ, so only the nearer ones reach the hand.
// The boundary is the surface stage's (SimState::shared.surface): app builds a surface stage
// wherever it builds this one, and the assembled state carries the first surface.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "contact/blade_resistance.h"
#include "engine/contact_plane.h"
#include "engine/geometry/surface_bvh.h"
#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"
#include "engine/state_blocks.h"
#include "engine/surface_mesh.h"
#include "engine/tissue_stress.h"

namespace serosa::contact {

inline constexpr double kJawRadius = 0.001;          ///< m
inline constexpr double kContactStiffness = 200.0;   ///< N/m per node
inline constexpr double kContactBeta = 0.5;          ///< cap: beta m / dt^2
inline constexpr double kGraspCloseRad = 0.2;        ///< rad
inline constexpr double kGraspHysteresisRad = 0.05;  ///< rad
inline constexpr double kGraspHalfWidth = 0.003;     ///< m
inline constexpr double kHapticRange = 0.01;         ///< tip to surface, m: farther, no plane
inline constexpr double kCueRange = 0.05;            ///< tip to surface, m: the depth cue's reach
inline constexpr double kHapticStiffness = 500.0;    ///< rendered contact stiffness, N/m

/// What the stage computes besides the forces it applies (nothing it is not asked for).
struct ContactOutputs {
  /// The haptic contact planes and the reactions (only when a haptic loop renders them: no BVH,
  /// no cost otherwise).
  bool haptic_planes = false;
  /// The reactions' blade load of closing scissors (the haptic loop's jaw torque, the metrics'
  /// scissors force); on with haptic_planes.
  bool blade_load = false;
};

/// (tools) number of nodes each tool holds (graspers; none for every tool without a contact stage).
[[nodiscard]] std::vector<std::size_t> grasped_counts(const SimState& state);

class ToolContactStage final : public Stage {
 public:
  ToolContactStage(const Scene& scene, LameTable lame, ContactOutputs outputs = {});

  [[nodiscard]] std::string_view name() const noexcept override { return "contact"; }
  void step(const StepContext& ctx, SimState& state) override;
  /// The grasps are SimState::blocks.contact; a restored state's are checked against the mesh
  /// and the tools, and the BVH and the boundary are rebuilt.
  void adopt(SimState& state) override;

  /// Nodes pushed by contact in the last step, over all tools.
  [[nodiscard]] std::int64_t contacts() const noexcept { return m_contacts; }

 private:
  using Grasp = ContactBlock::Grasp;
  /// Another grasper's grasp that holds the node, if any.
  [[nodiscard]] static const Grasp* held_elsewhere(const SimState& state, std::int32_t node,
                                                   const Grasp& self);
  void refresh_boundary(const SimState& state);
  void resist_blades(const SimState& state, std::size_t tool, Grasp& g);
  void grab(SimState& state, std::size_t tool, Grasp& g);
  void release(SimState& state, Grasp& g);
  /// An instrument withdrawn into its port: lets go of what it held.
  void withdraw(SimState& state, Grasp& g);
  /// What each grasper holds, for the metrics (SimState::shared.grasped).
  static void publish_grasps(SimState& state);
  void update_planes(SimState& state);

  std::vector<ToolKind> m_kinds;
  std::vector<std::optional<Vec3>> m_trocars;
  LameTable m_lame;
  std::vector<std::int32_t> m_boundary;      // surface node ids
  std::uint64_t m_boundary_version = ~0ull;  // surface the boundary was taken from
  std::int32_t m_boundary_nodes = -1;
  std::vector<Vec3> m_force;         // (n) external forces of this step
  std::vector<std::uint8_t> m_flag;  // (n) scratch
  std::vector<Vec3> m_tool_force;    // (tools)
  std::int64_t m_contacts = 0;
  bool m_haptic = false;      // planes and reactions
  bool m_blade_load = false;  // reactions' blade load (with m_haptic, or for the metrics)
  geometry::SurfaceBvh m_bvh;
  std::uint64_t m_bvh_version = ~0ull;
  std::vector<std::optional<ContactPlane>> m_planes;  // (tools), none: endoscope, out of range
  std::vector<std::optional<ContactPlane>> m_near;    // (tools) the same out to kCueRange
  std::vector<ToolReaction> m_reactions;              // (tools) this step's
  BladeResistance m_blades;                           // node volumes and strengths
  std::int64_t m_blade_nodes = -1;                    // node count m_blades was updated for
};

}  // namespace serosa::contact
