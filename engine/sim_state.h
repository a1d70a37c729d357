// SimState: everything that changes while a scene runs (docs/ARCHITECTURE.md "State").
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "engine/blood.h"
#include "engine/clip.h"
#include "engine/contact_plane.h"
#include "engine/smoke.h"
#include "engine/state_blocks.h"
#include "engine/surface_mesh.h"
#include "engine/tet_mesh.h"
#include "engine/tool_state.h"
#include "engine/topology_delta.h"

namespace serosa {

/// One cut applied to the mesh during a step, as the cutting stage hands it on.
/// CutEvent::tool of a cut no tool made: a polygon an engineer asked for (serosa.Simulation.cut).
inline constexpr std::size_t kNoTool = static_cast<std::size_t>(-1);

struct CutEvent {
  std::uint64_t step = 0;                     ///< solver step during which it happened
  std::size_t tool = 0;                       ///< index into Scene::tools, or kNoTool
  int blade = 0;                              ///< 0 or 1 (engine/tool_geometry.h)
  std::vector<Vec3> polygon_m;                ///< (k) the swept blade polygon, m
  TopologyDelta delta;                        ///< as applied (its filled-in fields set)
  std::vector<Vec3> removed_centroids_m;      ///< (r) current centroid of each removed tet, m
  std::vector<double> removed_volumes_m3;     ///< (r) rest volume of each removed tet, m^3
  std::vector<std::uint16_t> removed_groups;  ///< (r) group of each removed tet
};

/// The tissue's pull and torque on one tool, for the haptic loop (contact/tool_contact_stage.h).
struct ToolReaction {
  Vec3 held_pull_n = Vec3::Zero();  ///< the grasped tissue's elastic pull on a grasper's jaws, N
  double jaw_torque_nm = 0.0;       ///< tissue between closing scissor blades, N m (+ opens)
  double blade_force_n = 0.0;  ///< the shear force each closing scissor blade presses it with, N
  Vec3 shaft_push_n = Vec3::Zero();  ///< the tissue's push on the shaft, N
  /// where it acts: distance from the port over the port-to-tip distance (0: at the port, 1: at
  /// the tip)
  double shaft_lever = 0.0;
};

/// The messages of a step: one stage writes a field every step it runs, later stages of this step
/// (or, for the cuts, the FEM stage of the next) read it; it carries nothing from one step to the
/// next that a stage relies on (docs/ARCHITECTURE.md "The step").
struct StepEvents {
  /// contact -> FEM: external node forces for this step's solve, N; (n), or empty for none.
  std::vector<Vec3> external_force_n;
  /// contact -> FEM: held nodes were moved with the jaws this step (the jaws' work, which the
  /// FEM's energy guard must not take for a gain of its solve).
  bool nodes_moved = false;
  /// contact -> metrics: each tool's force on the tissue this step, N; (tools), or empty when no
  /// contact stage runs. (Closing scissor blades press the tissue from both sides: no net force;
  /// their load is tool_reactions' blade_force_n.)
  std::vector<Vec3> tool_force_n;
  /// contact -> haptics: each tool's local contact plane; (tools), or empty when no haptic loop
  /// asked for planes.
  std::vector<std::optional<ContactPlane>> contact_planes;
  /// contact -> render: each tool's nearest organ surface point and its outward normal out to a
  /// longer reach than the contact planes' (the picture's depth cue); (tools), or empty like
  /// contact_planes.
  std::vector<std::optional<ContactPlane>> tissue_near;
  /// contact -> haptics: what each tool feels from the tissue besides its tip's contact plane;
  /// (tools), or empty when no haptic loop asked for it.
  std::vector<ToolReaction> tool_reactions;
  /// cutting -> surface and metrics (this step) and FEM (the next step's): the cuts of this step,
  /// in order; cleared by the cutting stage before it cuts.
  std::vector<CutEvent> cuts;
};

/// What stages publish for the others and keep from step to step: each field is written by one
/// stage, from its block of the state or from the mesh, and read by later stages, the view and the
/// reports. Stages never call each other (docs/ARCHITECTURE.md "The step").
struct SharedState {
  /// contact -> metrics: the nodes each grasper holds now, ids; (tools), empty for a tool that
  /// holds nothing (written when a grasp begins or ends).
  std::vector<std::vector<std::int32_t>> grasped;
  /// clips -> cutting, render, metrics: every clip placed so far, where the tissue carries it now
  /// (contact/clip_stage.h); empty when no clips stage runs.
  std::vector<Clip> clips;
  /// metrics -> render: where the artery bleeds (each cut through it while unsecured) and since
  /// when: (k) {where, m; time, s}, in the order they began (metrics/procedure_errors.h).
  std::vector<std::pair<Vec3, double>> bleeds;
  /// bleeding -> render: the blood of each bleeding in `bleeds`, in the same order
  /// (metrics/bleeding_stage.h); empty when the effect is not listed.
  std::vector<Blood> blood;
  /// smoke -> render: the puffs the hook's coagulation raised that have not cleared yet
  /// (cutting/smoke_stage.h); empty when the effect is not listed.
  std::vector<SmokePuff> smoke;
  /// surface -> contact, render, pictures: the boundary surface, kept up to date by the surface
  /// stage (empty when no surface stage runs).
  SurfaceMesh surface;
};

/// The mutable state of a running scene. The scene model (engine/scene/scene.h) is read-only after
/// load; this is what stages write. Copyable: snapshots, tests and benchmarks copy it.
struct SimState {
  double time_s = 0.0;           ///< simulated time, s
  std::uint64_t step = 0;        ///< solver steps taken
  TetMesh mesh;                  ///< all organs of the scene in one mesh (groups tell them apart)
  std::vector<ToolState> tools;  ///< (tools) latest consumed input per scene tool, scene order
  StepEvents events;             ///< this step's messages between stages
  SharedState shared;            ///< what stages publish for the others, kept between steps
  StageBlocks blocks;            ///< each stage's own part of the state (engine/state_blocks.h)
};

/// 64-bit FNV-1a hash of the state: time, step, topology, positions, velocities and Dirichlet
/// flags, tool inputs, the forces handed from contact to FEM and metrics. The stages' own parts of
/// the whole state are compared whole in a replay's snapshots (engine/state_codec.h).
/// Equal states (bit for bit) give equal hashes; used by recordings and regression reports.
[[nodiscard]] std::uint64_t state_hash(const SimState& s);

}  // namespace serosa
