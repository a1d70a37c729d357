// Scene model: what a scene file describes (organs, materials, solver, tools, effects), parsed
// and validated once by load_scene and read-only afterwards (docs/ARCHITECTURE.md "Data model").
// Every key, its unit, default and range is documented in docs/scene-format.md; the defaults
// below are the ones the loader applies when a key is absent.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "engine/scene/rubric.h"

namespace serosa {

// ---------------------------------------------------------------------------------------------
// Effects: what the scene simulates. app builds one stage per listed effect and nothing else.

/// One effect a scene may list. Enum order is the canonical listing order (not the stage order,
/// which the runner fixes).
enum class Effect : std::uint8_t {
  kFem,         ///< "fem": corotational linear FEM of every organ
  kGravity,     ///< "gravity": body force density * gravity (needs fem)
  kSupports,    ///< "supports": the [[support]] planes the organs rest on (needs fem)
  kPlasticity,  ///< "plasticity": Müller-Gross plastic strain (needs fem)
  kCutting,     ///< "cutting": scissors cut tets along the swept blade
  kClips,       ///< "clips": clip appliers place clips that clamp tissue (needs contact)
  kLoops,       ///< "loops": endoloops ligate the tissue they are cinched around (needs contact)
  kCautery,     ///< "cautery": a hook divides and coagulates tissue while its pedal is pressed
  kContact,     ///< "contact": tool-organ contact forces (needs fem and surface)
  kSurface,     ///< "surface": boundary surface extraction, normals, collision BVH
  kHaptics,     ///< "haptics": the 1 kHz force loop (needs a tool driven by a device)
  kRender,      ///< "render": endoscope view (needs surface)
  kRecord,      ///< "record": record inputs and state hashes to a .lapr file
  /// "bleeding": a cut unsecured artery bleeds, a pulsing stream and a pool that stains the
  /// tissue below, until a ligature or the hook's coagulation closes it (needs metrics.artery)
  kBleeding,
  /// "smoke": the hook's coagulation raises smoke that drifts up and clears (needs cautery)
  kSmoke,
};
inline constexpr std::size_t kNumEffects = 15;

/// Every effect in enum order.
inline constexpr Effect kAllEffects[kNumEffects] = {
    Effect::kFem,     Effect::kGravity, Effect::kSupports, Effect::kPlasticity, Effect::kCutting,
    Effect::kClips,   Effect::kLoops,   Effect::kCautery,  Effect::kContact,    Effect::kSurface,
    Effect::kHaptics, Effect::kRender,  Effect::kRecord,   Effect::kBleeding,   Effect::kSmoke};

/// The scene-file name of an effect ("fem", "gravity", ...).
[[nodiscard]] std::string_view effect_name(Effect e) noexcept;
/// The effect with that scene-file name, or nullopt.
[[nodiscard]] std::optional<Effect> effect_from_name(std::string_view name) noexcept;

// ---------------------------------------------------------------------------------------------
// Enumerated settings. Each has a name <-> enum pair; names are the scene-file spellings.

enum class Quality : std::uint8_t { kFast, kBalanced, kAccurate };
enum class SolverKind : std::uint8_t { kPcg, kCholmod, kPcgCholmod, kPcgLagged };
enum class ToolKind : std::uint8_t {
  kScissors,
  kGrasper,
  kEndoscope,
  kClipApplier,
  kHook,
  kEndoloop,
  kStapler  ///< a linear cutter-stapler (engine/stapler.h)
};
/// What drives a tool: a USB rig's handle, the emulated rig, the mouse, a scripted path, or a
/// Python program (serosa.Simulation.set_tool; anywhere else such a tool stays where it is).
enum class DeviceKind : std::uint8_t { kRig, kRigEmulated, kMouse, kScript, kPython };
enum class Hand : std::uint8_t { kLeft, kRight };
enum class CutMethod : std::uint8_t { kPattern, kRemove, kSnap };
/// What a scissors stroke whose blades bent out of one plane is cut along: its swept surface, or
/// the plane that fits it best.
enum class StrokeSurfaceKind : std::uint8_t { kSwept, kPlane };
/// What the endoscope sees around the organs: nothing (a black void) or an abdomen.
enum class Surroundings : std::uint8_t { kNone, kAbdomen };

[[nodiscard]] std::string_view quality_name(Quality q) noexcept;         ///< fast|balanced|accurate
[[nodiscard]] std::string_view solver_kind_name(SolverKind k) noexcept;  ///< pcg|cholmod|...
[[nodiscard]] std::string_view tool_kind_name(
    ToolKind k) noexcept;  ///< scissors|...|clip-applier|hook|endoloop
[[nodiscard]] std::string_view device_kind_name(DeviceKind k) noexcept;  ///< rig|...|script|python
[[nodiscard]] std::string_view hand_name(Hand h) noexcept;               ///< left|right
[[nodiscard]] std::string_view cut_method_name(CutMethod m) noexcept;    ///< pattern|remove|snap
[[nodiscard]] std::string_view stroke_surface_name(StrokeSurfaceKind k) noexcept;  ///< swept|plane
[[nodiscard]] std::string_view surroundings_name(Surroundings s) noexcept;         ///< none|abdomen

[[nodiscard]] std::optional<Quality> quality_from_name(std::string_view s) noexcept;
[[nodiscard]] std::optional<SolverKind> solver_kind_from_name(std::string_view s) noexcept;
[[nodiscard]] std::optional<ToolKind> tool_kind_from_name(std::string_view s) noexcept;
/// Device kinds without argument: "rig", "rig-emulated", "mouse", "python" (and "script" alone,
/// which the loader rejects: a script needs ":FILE").
[[nodiscard]] std::optional<DeviceKind> device_kind_from_name(std::string_view s) noexcept;
[[nodiscard]] std::optional<Hand> hand_from_name(std::string_view s) noexcept;
[[nodiscard]] std::optional<CutMethod> cut_method_from_name(std::string_view s) noexcept;
[[nodiscard]] std::optional<StrokeSurfaceKind> stroke_surface_from_name(
    std::string_view s) noexcept;
[[nodiscard]] std::optional<Surroundings> surroundings_from_name(std::string_view s) noexcept;

// ---------------------------------------------------------------------------------------------
// [scene]

struct SceneSettings {
  double dt_s = 0.005;                                       ///< solver step, s; 0 < dt <= 1
  Vec3 gravity_mps2 = Vec3(0.0, -9.81, 0.0);                 ///< gravity, m/s^2 (scene frame, y up)
  std::set<Effect> effects{Effect::kFem, Effect::kGravity};  ///< listed effects, enum order
  std::optional<Quality> quality;  ///< preset that chose the solver/render defaults, if given
  /// Displacement error the solver preset must stay within, relative (dimensionless, (0, 1)):
  /// `accuracy_target` in the scene, else the quality preset's target (engine/scene/presets.h).
  std::optional<double> accuracy_target;

  [[nodiscard]] bool has(Effect e) const { return effects.count(e) != 0; }
};

// ---------------------------------------------------------------------------------------------
// [[organ]]

/// Rayleigh damping C = mass * M + stiffness * K.
struct RayleighDamping {
  double mass_per_s = 0.1;    ///< mass-proportional coefficient, 1/s; >= 0
  double stiffness_s = 0.01;  ///< stiffness-proportional coefficient, s; >= 0
};

/// Plastic flow (Müller & Gross 2004): strain beyond `yield` creeps into the plastic strain at
/// rate `creep`, whose norm is capped at `max`. Used only when the plasticity effect is listed.
struct PlasticityParams {
  double yield = 0.05;       ///< elastic limit, strain norm (dimensionless); >= 0
  double creep_per_s = 0.5;  ///< creep rate, 1/s; >= 0
  double max = 0.3;          ///< plastic strain norm cap (dimensionless); >= 0
};

/// A linear elastic tissue.
struct Material {
  double young_pa = 5.0e3;        ///< Young's modulus, Pa; > 0
  double poisson = 0.45;          ///< Poisson's ratio; -1 < nu < 0.5
  double density_kgpm3 = 1.05e3;  ///< mass density, kg/m^3; > 0
  RayleighDamping damping;        ///< Rayleigh damping
  PlasticityParams plasticity;    ///< plastic flow parameters
};

/// Axis-aligned box in the scene frame, m. min <= max componentwise.
struct Box {
  Vec3 min_m = Vec3::Zero();  ///< lower corner, m
  Vec3 max_m = Vec3::Zero();  ///< upper corner, m
  /// True when p lies inside or on the box.
  [[nodiscard]] bool contains(const Vec3& p) const;
};

/// Dirichlet nodes: a node is fixed when any of the three selections picks it.
struct FixedSpec {
  std::optional<Box> box;           ///< nodes whose transformed rest position lies in the box
  std::vector<int> groups;          ///< nodes of any tet of these group ids (sorted, unique)
  std::vector<std::int32_t> nodes;  ///< node ids in mesh-file order, 0-based (sorted, unique)
  [[nodiscard]] bool empty() const { return !box && groups.empty() && nodes.empty(); }
};

/// Placement of an organ's mesh in the scene frame: p_scene = translate + R * (scale * p_mesh),
/// R = Rz(rz) * Ry(ry) * Rx(rx) (rotations about the fixed scene axes, x first).
struct OrganTransform {
  Vec3 translate_m = Vec3::Zero();  ///< translation, m
  Vec3 rotate_deg = Vec3::Zero();   ///< rotation angles about x, y, z, degrees
  double scale = 1.0;               ///< uniform scale (dimensionless; 0.001 for a mesh in mm)

  [[nodiscard]] bool is_identity() const;
  [[nodiscard]] Mat3 rotation() const;                 ///< R
  [[nodiscard]] Vec3 apply(const Vec3& p_mesh) const;  ///< p_scene, m
};

struct Organ {
  std::string name;                         ///< unique among organs
  std::filesystem::path mesh;               ///< mesh file, resolved against the scene file's folder
  std::map<int, std::string> groups;        ///< group id (Gmsh physical tag) -> name; may be empty
  Material material;                        ///< material of every group without an override
  std::map<int, Material> group_materials;  ///< complete materials of overridden group ids
  FixedSpec fixed;                          ///< Dirichlet nodes (attachments to the body wall)
  OrganTransform transform;                 ///< mesh -> scene frame

  /// The material of the tets of group `group` (its override, else the organ's material).
  [[nodiscard]] const Material& material_for(int group) const;
  /// The id of the group named `name`, or nullopt.
  [[nodiscard]] std::optional<int> group_id(std::string_view name) const;
};

// ---------------------------------------------------------------------------------------------
// [[support]]

/// A support the organs rest on under gravity (the posterior abdominal wall, a bowel loop's
/// side): a rigid plane that pushes back on tissue below it. The organs lie on the side the
/// normal points to.
struct Support {
  std::string name;             ///< unique among supports (reports and errors name it)
  Vec3 point_m = Vec3::Zero();  ///< a point of the plane, m
  Vec3 normal = Vec3::UnitZ();  ///< unit normal, towards the organs (normalised by the loader)
};

// ---------------------------------------------------------------------------------------------
// [solver] [render] [[tool]] [record] [cutting] [headless]

struct SolverSettings {
  SolverKind kind = SolverKind::kPcg;  ///< linear solver of the implicit step
  double tolerance = 1e-6;             ///< relative residual for PCG; > 0, < 1
  int max_iterations = 100;            ///< PCG iteration cap; >= 1
  int refresh_iterations = 2;          ///< pcg-lagged: refresh the factor above this; >= 0
  int factor_lag_steps = 12;           ///< pcg-lagged: steps a refresh may take; >= 1
  int urgent_lag_steps = 6;            ///< pcg-lagged: the same for urgent refreshes; >= 1
  int cut_lag_steps = 20;  ///< pcg-lagged: the same after a cut, when more than factor_lag_steps
  /// pcg-lagged: patch the rows of nodes whose tets turned otherwise than they did since the
  /// factor's step by more than this, rad; 0: never; within [0, pi].
  double misfit_rad = 0.2;
  /// pcg-lagged: rings of neighbours around the patched nodes (a cut's, a grasp's, a misfit's)
  /// in the patch; within [0, 8].
  int patch_rings = 2;
  /// pcg-lagged after a cut: patch the factor on the touched rows until a refresh is in (true:
  /// "patch"), or factor the new matrix on the step after the cut (false: "factor").
  bool patch_after_cut = true;
  /// OpenMP threads of the solver thread's loops; 1..256. One by default: on two cores the
  /// other one serves the background factorization, the renderer and the haptic loop.
  int threads = 1;
};

/// The solver of a scene that does not set one: the one every shipped scene uses, pcg-lagged to a
/// relative residual of 1e-3 in at most 200 iterations, which converges on their kind of mesh
/// (SolverSettings{} is plain PCG to 1e-6 in 100, which did not on a 112-node bead).
[[nodiscard]] SolverSettings scene_default_solver();

/// The tissues a group can be drawn as (`[render] looks`; render/materials.h draws each).
inline constexpr std::array<std::string_view, 12> kTissueLooks{
    "appendix", "mesoappendix", "artery",      "cecum", "colon",      "bowel",
    "ileum",    "liver",        "gallbladder", "fat",   "peritoneum", "stomach"};

struct RenderSettings {
  int tessellation = 3;        ///< Phong tessellation level; 1 = flat, 1..16
  double shape_factor = 0.75;  ///< Phong tessellation alpha; 0 = flat, 0..1
  int width = 1280;            ///< window or offscreen frame width, pixels; 1..16384
  int height = 720;            ///< window or offscreen frame height, pixels; 1..16384
  /// Drawn around the organs: an abdomen needs a [[support]] (drawn as the posterior wall).
  Surroundings surroundings = Surroundings::kNone;
  /// Group name -> the tissue it is drawn as (one of kTissueLooks); a group not listed is drawn
  /// as the tissue its own name names, if any, else in a palette colour.
  std::map<std::string, std::string> looks;
};

struct ToolDevice {
  DeviceKind kind = DeviceKind::kMouse;
  /// The tool path CSV (resolved, exists, has rows for the tool): for kScript the path the tool
  /// follows; for kRigEmulated the path the emulated rig's handle plays (then the process sets
  /// up the emulated rig itself), or empty when someone else emulates the rig (tests).
  std::filesystem::path script;
};

struct Tool {
  std::string name;  ///< unique among tools; the CSV's `tool` column
  ToolKind kind = ToolKind::kGrasper;
  ToolDevice device;             ///< what drives it
  std::optional<Hand> hand;      ///< rig handle that drives it (rig devices), if given
  std::optional<Vec3> trocar_m;  ///< trocar (abdominal wall port) position, m, if given
};

struct RecordSettings {
  std::optional<std::filesystem::path> path;  ///< .lapr output, resolved; else the CLI decides
  std::int64_t hash_every = 100;              ///< state hash every N solver steps; >= 1
  /// Whole-state snapshot every this much simulated time, s (0: none); >= 0. A replay restores
  /// one to start late (--from) or to seek back.
  double snapshot_every_s = 1.0;
};

struct CuttingSettings {
  CutMethod method = CutMethod::kPattern;  ///< pattern (paper), remove (delete tets), snap
  double tolerance =
      1e-3;  ///< node-on-plane tolerance relative to the tet's longest edge; [0, 0.5)
  /// A bent stroke is cut along its swept surface (pattern method only) or in its plane.
  StrokeSurfaceKind strokes = StrokeSurfaceKind::kSwept;
};

struct HeadlessSettings {
  std::int64_t steps = 1000;  ///< steps of `serosa headless` without --steps; >= 1
};

/// The steps an appendectomy is followed through, in their order (metrics/procedure_steps.h).
inline constexpr std::array<std::string_view, 5> kProcedureSteps = {
    "expose", "divide_mesentery", "secure_base", "transect", "extract"};

/// The groups an appendectomy's steps are judged on (metrics/procedure_steps.h).
struct ProcedureGroups {
  std::string specimen;   ///< what is taken out (the appendix)
  std::string base;       ///< what it is taken off, the stump's side (the cecum)
  std::string mesentery;  ///< the fold that carries its artery (the mesoappendix)
};

/// A grasp-and-transfer drill: an object carried from where it lies onto a target on the board
/// (metrics/transfer_watch.h).
struct TransferSettings {
  std::string object;            ///< the group carried (a bead): a group name of the organs
  Vec3 target_m = Vec3::Zero();  ///< where it should be set down, on the board, m
  double radius_m = 0.005;       ///< the target's radius across the board, m; > 0
};

/// What trainee metrics compare against (app's metrics stage).
struct MetricsSettings {
  /// The planned cut line, a polyline in the scene frame, m ((k) points, k = 0 or k >= 2).
  /// Empty: no cut-deviation metric.
  std::vector<Vec3> planned_cut_m;
  /// Half-width of the tolerance band around the planned cut line, m; > 0. Tets cut farther
  /// than this from the line count as collateral cut volume.
  double cut_band_m = 0.003;
  /// A tool pressing on the tissue harder than this counts towards force_over_s, N; > 0.
  double force_limit_n = 5.0;
  /// Above this von Mises stress the tissue would tear, Pa; none: no tears counted. The tissue is
  /// not torn (no tearing is simulated): each time the mesh's peak stress rises above it counts as
  /// a tear the trainee caused (`tears`).
  std::optional<double> tear_stress_pa;
  /// Points the endoscope should be brought to look at, in any order (a camera drill), m; (k).
  /// Empty: no target metrics.
  std::vector<Vec3> view_targets_m;
  /// The group that bleeds when a cut goes through it while no clip clamps it (the appendicular
  /// artery); none: no bleeding is watched for. A group name of one of the organs.
  std::optional<std::string> artery;
  /// Where the artery should be clipped, at rest, m (a point on it the instructor marks); none:
  /// no clip_target_error_m. Needs `artery`.
  std::optional<Vec3> clip_target_m;
  /// Groups a live hook must not touch (the cecum wall): coagulating them is a thermal injury.
  std::vector<std::string> protected_groups;
  /// A grasp-and-transfer drill is followed; none: no transfer metrics.
  std::optional<TransferSettings> transfer;
  /// The procedure's steps are followed (expose, divide the mesentery, secure the base,
  /// transect, extract); needs `artery`. None: no steps are reported.
  std::optional<ProcedureGroups> procedure;
  /// What the session is scored on (engine/scene/rubric.h); none: no assessment is reported.
  std::optional<Rubric> rubric;
};

/// A loaded, validated scene. Read-only after load.
struct Scene {
  std::filesystem::path file;  ///< the scene file as given (errors name it)
  SceneSettings settings;
  std::vector<Organ> organs;      ///< at least one
  std::vector<Support> supports;  ///< planes the organs rest on (effect "supports")
  SolverSettings solver;
  RenderSettings render;
  std::vector<Tool> tools;  ///< scene order = SimState::tools order
  RecordSettings record;
  CuttingSettings cutting;
  HeadlessSettings headless;
  MetricsSettings metrics;

  /// Index of the tool named `name` in `tools`, or nullopt.
  [[nodiscard]] std::optional<std::size_t> tool_index(std::string_view name) const;
};

/// Reads and validates a scene file. Throws InputError naming the file, the line and the key path
/// ("organ[0].young: must be > 0, got -5") on a TOML syntax error, an unknown key (the message
/// lists the allowed keys), a wrong type, an out-of-range value, a missing mesh or script file,
/// an unknown or duplicated effect, duplicate names and unmet effect dependencies.
[[nodiscard]] Scene load_scene(const std::filesystem::path& path);

/// Same on in-memory TOML; relative paths resolve against scene_path's folder and errors name
/// scene_path. Referenced mesh and script files must exist.
[[nodiscard]] Scene parse_scene_text(const std::string& toml,
                                     const std::filesystem::path& scene_path);

}  // namespace serosa
