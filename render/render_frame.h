// RenderFrame: the plain data the renderer draws. Filling it needs no GL and drawing it is a
// separate step (render/frame_renderer.h), so the solver thread can build frames and tests can
// check them without a context. No GL handles, no pointers into simulation state.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/session_summary.h"

namespace serosa::render {

/// A pinhole camera in world coordinates (m). The light sits at the eye (an endoscope's tip).
struct Camera {
  std::array<float, 3> eye{0.0f, 0.0f, 1.0f};     ///< camera position, m
  std::array<float, 3> target{0.0f, 0.0f, 0.0f};  ///< point looked at, m
  std::array<float, 3> up{0.0f, 1.0f, 0.0f};      ///< approximate up direction (need not be unit)
  float fov_y_deg = 70.0f;                        ///< vertical field of view, degrees
};

/// One surgical instrument to draw (plain data, world coordinates, m). Tool frame as in
/// docs/scene-format.md: local +z along the shaft from the handle towards the tip, local +y up,
/// the jaws open in the local x-z plane, hinged about local y.
struct RenderTool {
  enum class Kind : std::uint8_t {
    kScissors,     ///< two blades that shear past each other (Metzenbaum-like, slightly curved)
    kGrasper,      ///< two flat jaws that close on each other
    kClipApplier,  ///< drawn with a grasper's jaws (the clip it places is a RenderClip)
    kHook,         ///< an L-hook electrode: a thin wire beyond the shaft, its crook along +side
    /// a knot pusher with its suture loop: a ring normal to the shaft through the tip, centred
    /// along +side, its radius engine/endoloop.h's open radius scaled by the jaw channel
    kEndoloop,
    /// a linear cutter-stapler: a deep cartridge jaw and a thin anvil jaw, kCartridgeLength long
    /// (engine/stapler.h), hinged where the other instruments' jaws are
    kStapler,
  };
  Kind kind = Kind::kGrasper;
  std::array<float, 3> tip{0.0f, 0.0f, 0.0f};              ///< tip of the closed jaws, m
  std::array<float, 4> quat_wxyz{1.0f, 0.0f, 0.0f, 0.0f};  ///< orientation (normalised when drawn)
  bool has_trocar = false;                                 ///< trocar below is given
  /// Trocar (port in the abdominal wall), m: when given, the shaft runs from outside the body
  /// through this point to the jaws' hinge, and the tool's axis is the line trocar -> tip.
  std::array<float, 3> trocar{0.0f, 0.0f, 0.0f};
  float jaw_rad = 0.0f;          ///< jaw opening angle between the two jaws, rad, [0, pi]
  std::uint32_t scene_tool = 0;  ///< index of the scene tool it draws (scene order)
  bool active = false;           ///< the trainee's active instrument: drawn with a coloured collar
  /// The depth cue: the organ surface point nearest the tip (the contact stage's), m, and the
  /// tip's signed distance from it along the surface's outward normal, m (< 0: pressed in).
  /// A ring drawn on the tissue there closes in as the tip comes near and lights up at contact.
  bool has_tissue = false;
  std::array<float, 3> tissue_point{0.0f, 0.0f, 0.0f};
  std::array<float, 3> tissue_normal{0.0f, 0.0f, 1.0f};  ///< unit
  float tissue_distance_m = 0.0f;
  /// How much tissue lies between its open jaws, m: the extent, in the jaws' plane, of the organ
  /// surface crossing it between them (what a surgeon checks before closing: a 7 mm appendix
  /// between the blades reads about 7 mm, one they only graze much less); 0: none.
  float tissue_in_jaws_m = 0.0f;
};

/// A placed ligature (plain data, world coordinates, m): a clip's two legs along its centre
/// line, pressed together across it; a cinched loop, a suture ring round the middle of its axis;
/// or a staple line, a row of closed staples along its centre line.
struct RenderClip {
  std::array<float, 3> start{0.0f, 0.0f, 0.0f};   ///< clip: centre line, hinge end; loop: axis, m
  std::array<float, 3> end{0.0f, 0.0f, 1.0f};     ///< clip: centre line, far end; loop: axis, m
  std::array<float, 3> across{1.0f, 0.0f, 0.0f};  ///< unit: the direction the legs pressed
  bool loop = false;                              ///< a cinched endoloop
  bool staple = false;                            ///< a stapler's staple line
  float radius = 0.0f;                            ///< a loop's ring radius, m
};

/// Blood where an unsecured artery was cut (plain data, world coordinates, m): a dark red drop
/// welling at the cut end; with effect "bleeding", also the pulsing stream's droplets and the pool
/// on the surface below.
struct RenderBleed {
  std::array<float, 3> at{0.0f, 0.0f, 0.0f};           ///< the cut end, m
  float radius = 0.0f;                                 ///< the drop welling there, m
  std::array<float, 3> pool{0.0f, 0.0f, 0.0f};         ///< the pool's centre, m
  std::array<float, 3> pool_normal{0.0f, 1.0f, 0.0f};  ///< unit: the surface it lies on
  float pool_radius = 0.0f;                            ///< m; 0: no pool
  std::vector<std::array<float, 3>> stream;  ///< the stream's droplets, m; empty: not flowing
};

/// A puff of surgical smoke (plain data, world coordinates, m): a soft grey cloud, drawn over the
/// visual view's surfaces.
struct RenderPuff {
  std::array<float, 3> at{0.0f, 0.0f, 0.0f};  ///< centre, m
  float radius = 0.0f;                        ///< m
  float density = 0.0f;  ///< how much it hides what lies behind its centre, [0, 1]
};

/// One named number the overlay lists (instructor metrics: cut length, time in contact, force
/// peaks ...), e.g. {"max force", 1.8, "N"}.
struct OverlayMetric {
  std::string name;
  double value = 0.0;
  std::string unit;  ///< SI unit symbol, may be empty
};

/// An error marked on the replay's timeline.
struct TimelineMark {
  double time_s = 0.0;    ///< when it happened, s
  std::string what;       ///< in words: "bleeding: the artery was cut before it was secured"
  std::string criterion;  ///< the rubric's criterion it shows ("bleeding_events"); may be empty
};

/// The replay's metric timeline: the tools' force on the tissue over the recording, pooled into
/// bins of equal time, and the errors marked where they happened.
struct OverlayTimeline {
  std::vector<float> force_n;  ///< (bins) largest tool force in each bin, N; < 0: not known yet
  std::vector<TimelineMark> marks;  ///< errors found so far, in time order
  double known_s = 0.0;             ///< the timeline is computed up to here, s
  bool done = false;                ///< computed to the recording's end
  int current = -1;                 ///< the mark last jumped to; -1: none
};

/// What the overlay shows (plain data; drawn by Overlay, render/overlay.h). Negative or zero
/// rates mean "not running" and are shown as such.
/// One instrument in the trainee's hands, as the session's overlay lists it.
struct OverlayHand {
  std::string hand;                ///< "left", "right"
  std::string tool;                ///< the instrument's name in the scene
  bool active = false;             ///< the one the mouse steers now
  double jaw_rad = 0.0;            ///< its jaw opening, rad
  double jaw_max_rad = 0.0;        ///< how far it opens, rad (0: no jaws)
  bool pedal = false;              ///< its cautery pedal is down
  bool has_pedal = false;          ///< it has one (a hook)
  bool has_tissue = false;         ///< tissue_distance_m is known
  double tissue_distance_m = 0.0;  ///< the tip's distance to the nearest tissue, m (< 0: in it)
  double tissue_in_jaws_m = 0.0;   ///< how much tissue lies between its open jaws, m
  std::size_t holding_nodes = 0;   ///< surface nodes its closed jaws hold (a grasper), count
  bool entering = false;           ///< just taken: it waits in its port for the handle
};

struct OverlayData {
  bool visible = true;
  /// The trainee's instruments (the session): named, the active one marked, with their jaws,
  /// pedal and distance to tissue; empty: not shown.
  std::vector<OverlayHand> hands;
  /// The instruments waiting in their ports for an exchange, by name (the session).
  std::vector<std::string> waiting;
  bool help = false;             ///< the controls panel (overlay_help_lines) is shown
  double sim_time_s = 0.0;       ///< simulated time, s
  double fem_ms_per_step = 0.0;  ///< wall time of the last solver steps (mean), ms
  double solver_rate_hz = 0.0;   ///< solver steps per wall second, Hz
  /// The solver's pace: simulated seconds per wall second over the last second (1: real time);
  /// <= 0: not measured yet.
  double real_time_factor = 0.0;
  double haptic_rate_hz = 0.0;  ///< haptic loop rate, Hz; <= 0: no haptic loop
  /// What drives the instruments, a string literal: "mouse", "rig", "rig not connected",
  /// "emulated rig", "emulated rig not connected", "script", "recording"; null: not shown.
  const char* instruments = nullptr;
  /// The window's measured frame rate, frames/s, and the tessellation it draws with now (the
  /// renderer steps them down when the solver falls behind, window/frame_pacer.h); <= 0: unknown.
  double frame_rate_hz = 0.0;
  int drawn_tessellation = 0;
  float drawn_scale = 1.0f;  ///< the fraction of the window's resolution drawn at
  std::int64_t cuts = 0;     ///< topology changes (cuts) applied so far
  bool paused = false;       ///< the simulation is paused
  bool slow_motion = false;  ///< the solver cannot keep up with real time
  /// Replay timeline (instructors): shown when `replay` is true.
  bool replay = false;
  double replay_position_s = 0.0;  ///< position in the recording, s
  double replay_duration_s = 0.0;  ///< length of the recording, s
  double replay_speed = 1.0;       ///< playback speed, x real time (> 0)
  OverlayTimeline timeline;        ///< the metric timeline and its error marks (replays)
  /// A branch taken over from the replay: who drives what, one line ("BRANCH at 0:05.2 (step
  /// 1041): the mouse drives grasper (left), scissors (right); the recording drives the rest");
  /// empty: not branched. Shown in a coloured band above the timeline.
  std::string branch;
  /// The run's debrief beside the replay (render/session_summary.h), once the timeline has
  /// assessed the recording; none before (or without a rubric).
  std::optional<SessionSummary> debrief;
  std::vector<OverlayMetric> metrics;  ///< listed under the statistics, in this order
};

/// What a triangle of the scenery is made of (its colour: render/materials.h scenery_material).
enum class SceneryMaterial : std::uint8_t {
  kPeritoneum,  ///< the posterior abdominal wall's wet peritoneum
  kBowel,       ///< small bowel loops
  kFat,         ///< mesenteric fat
};

/// The static surroundings of the organs (an abdomen: render/scenery.h), drawn around them in the
/// visual view only. Plain data, world coordinates. Shapes: n vertices, t triangles.
struct Scenery {
  std::vector<float> pos;                 ///< (n x 3) vertex positions, m
  std::vector<float> nrm;                 ///< (n x 3) unit normals
  std::vector<std::uint32_t> tri;         ///< (t x 3) vertex ids, counter-clockwise from outside
  std::vector<SceneryMaterial> material;  ///< (t) what each triangle is made of
  /// Identifies the contents: a FrameRenderer uploads the scenery only when it (or the triangle
  /// count) differs from its last upload, so change it whenever the arrays change. 0 with empty
  /// arrays: no scenery.
  std::uint64_t version = 0;

  [[nodiscard]] std::size_t num_vertices() const { return pos.size() / 3; }
  [[nodiscard]] std::size_t num_triangles() const { return tri.size() / 3; }
  [[nodiscard]] bool empty() const { return tri.empty(); }
};

/// One frame to draw: the organs' boundary surface (and optionally the tet edges), the camera.
///
/// Shapes: n vertices, t triangles, e edges. `pos` may hold more vertices than the triangles use
/// (all tet nodes, say, so that `edges` can index interior nodes); unused vertices are not drawn
/// in the visual and collision views.
struct RenderFrame {
  std::vector<float> pos;  ///< (n x 3) vertex positions, m
  std::vector<float> nrm;  ///< (n x 3) unit normals; empty: computed when drawn
  /// (n x 3) rest (material) positions, m: the tissue's pattern (render/tissue_pattern.h) is laid
  /// out in them, so it stays on the tissue as it deforms and is cut; empty: laid out in pos.
  /// Changes only with the topology (bump topology_version).
  std::vector<float> rest;
  /// (n) 1 on a cut face's corners that also lie on the uncut surface (the wound's rim, where it
  /// oozes), 0 elsewhere; empty: no rim. Changes only with the topology.
  std::vector<float> rim;
  /// (n) how much blood stains each vertex, [0, 1] (effect "bleeding"); empty: none.
  std::vector<float> stain;
  /// Where a cecum's taeniae run, in rest coordinates (m): from the centre of the cecum towards
  /// where the appendix leaves it, unit axis; a zero axis: none drawn.
  std::array<float, 3> taenia_centre{0.0f, 0.0f, 0.0f};
  std::array<float, 3> taenia_axis{0.0f, 0.0f, 0.0f};
  std::vector<std::uint32_t> tri;  ///< (t x 3) vertex ids, counter-clockwise seen from outside
  std::vector<std::uint16_t> tri_group;  ///< (t) visual group (Gmsh physical tag) of each triangle
  /// (t) 1 = face made by a cut (wound), 2 = coagulated by a hook (charred), else 0
  std::vector<std::uint8_t> tri_cut;
  /// (e x 2) vertex ids of the tet edges, for the mechanical view. Optional: when empty, the
  /// mechanical view draws the triangles' edges instead.
  std::vector<std::uint32_t> edges;
  /// Optional names of the groups, indexed by group id ("appendix", "mesoappendix", "cecum",
  /// "liver", ...): a known name picks its material, anything else a palette colour by id.
  std::vector<std::string> group_names;
  /// The mesh's topology version: a FrameRenderer re-uploads indices and per-triangle materials
  /// only when it (or the triangle or edge count) changes; bump it whenever tri, tri_group,
  /// tri_cut, edges or group_names change.
  std::uint64_t topology_version = 0;
  /// Bump it when tri_cut changes without a topology change (a hook coagulating): the renderer
  /// then re-uploads the per-triangle materials.
  std::uint64_t material_version = 0;
  Camera camera;
  /// Instruments, drawn in every view (their meshes are generated each frame: render/tool_mesh.h).
  std::vector<RenderTool> tools;
  /// Placed clips, drawn in every view (render/tool_mesh.h append_clip_mesh).
  std::vector<RenderClip> clips;
  /// Bleeding, drawn in every view (render/tool_mesh.h append_bleed_mesh).
  std::vector<RenderBleed> bleeds;
  /// Surgical smoke, drawn over the visual view (blended, after its surfaces).
  std::vector<RenderPuff> smoke;
  /// (k) a polyline drawn as a thin violet marker in every view (the planned cut: where the
  /// trainee should cut), m; empty: none.
  std::vector<std::array<float, 3>> guide;
  /// The organs' surroundings (the abdomen around them), drawn in the visual view only; set once
  /// per scene, not per frame (it is uploaded only when its version changes). Empty: a black void.
  Scenery scenery;
  OverlayData overlay;

  [[nodiscard]] std::size_t num_vertices() const { return pos.size() / 3; }
  [[nodiscard]] std::size_t num_triangles() const { return tri.size() / 3; }
};

/// Checks shapes and ids: pos a multiple of 3; nrm and rest empty or as long as pos; rim and stain
/// empty or one per vertex; tri a multiple of 3
/// with ids < n; tri_group and tri_cut empty or one per triangle; edges a multiple of 2 with ids
/// < n; tools with finite poses and jaw_rad in [0, pi]; the scenery's pos a multiple of 3, nrm as
/// long as pos, tri a multiple of 3 with ids below its vertex count, one material per triangle,
/// finite positions and normals. Returns one message per problem; empty == valid.
[[nodiscard]] std::vector<std::string> validate(const RenderFrame& frame);

}  // namespace serosa::render
