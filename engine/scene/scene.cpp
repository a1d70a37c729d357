// Scene model helpers: enum names and the small queries on the model structs. The loader is in
// scene_load.cpp.
#include "engine/scene/scene.h"

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

namespace serosa {

SolverSettings scene_default_solver() {
  SolverSettings s;
  s.kind = SolverKind::kPcgLagged;
  s.tolerance = 1e-3;
  s.max_iterations = 200;
  return s;
}

namespace {

template <class E, std::size_t N>
using NameTable = std::array<std::pair<E, std::string_view>, N>;

constexpr NameTable<Effect, kNumEffects> kEffectNames{{{Effect::kFem, "fem"},
                                                       {Effect::kGravity, "gravity"},
                                                       {Effect::kSupports, "supports"},
                                                       {Effect::kPlasticity, "plasticity"},
                                                       {Effect::kCutting, "cutting"},
                                                       {Effect::kClips, "clips"},
                                                       {Effect::kLoops, "loops"},
                                                       {Effect::kCautery, "cautery"},
                                                       {Effect::kContact, "contact"},
                                                       {Effect::kSurface, "surface"},
                                                       {Effect::kHaptics, "haptics"},
                                                       {Effect::kRender, "render"},
                                                       {Effect::kRecord, "record"},
                                                       {Effect::kBleeding, "bleeding"},
                                                       {Effect::kSmoke, "smoke"}}};
constexpr NameTable<Quality, 3> kQualityNames{
    {{Quality::kFast, "fast"}, {Quality::kBalanced, "balanced"}, {Quality::kAccurate, "accurate"}}};
constexpr NameTable<SolverKind, 4> kSolverNames{{{SolverKind::kPcg, "pcg"},
                                                 {SolverKind::kCholmod, "cholmod"},
                                                 {SolverKind::kPcgCholmod, "pcg-cholmod"},
                                                 {SolverKind::kPcgLagged, "pcg-lagged"}}};
constexpr NameTable<ToolKind, 7> kToolKindNames{{{ToolKind::kScissors, "scissors"},
                                                 {ToolKind::kGrasper, "grasper"},
                                                 {ToolKind::kEndoscope, "endoscope"},
                                                 {ToolKind::kClipApplier, "clip-applier"},
                                                 {ToolKind::kHook, "hook"},
                                                 {ToolKind::kEndoloop, "endoloop"},
                                                 {ToolKind::kStapler, "stapler"}}};
constexpr NameTable<DeviceKind, 5> kDeviceNames{{{DeviceKind::kRig, "rig"},
                                                 {DeviceKind::kRigEmulated, "rig-emulated"},
                                                 {DeviceKind::kMouse, "mouse"},
                                                 {DeviceKind::kScript, "script"},
                                                 {DeviceKind::kPython, "python"}}};
constexpr NameTable<Hand, 2> kHandNames{{{Hand::kLeft, "left"}, {Hand::kRight, "right"}}};
constexpr NameTable<CutMethod, 3> kCutMethodNames{
    {{CutMethod::kPattern, "pattern"}, {CutMethod::kRemove, "remove"}, {CutMethod::kSnap, "snap"}}};

constexpr NameTable<StrokeSurfaceKind, 2> kStrokeSurfaceNames{
    {{StrokeSurfaceKind::kSwept, "swept"}, {StrokeSurfaceKind::kPlane, "plane"}}};

constexpr NameTable<Surroundings, 2> kSurroundingsNames{
    {{Surroundings::kNone, "none"}, {Surroundings::kAbdomen, "abdomen"}}};

template <class E, std::size_t N>
std::string_view name_of(const NameTable<E, N>& table, E e) noexcept {
  for (const auto& [value, name] : table) {
    if (value == e) return name;
  }
  return "?";
}

template <class E, std::size_t N>
std::optional<E> value_of(const NameTable<E, N>& table, std::string_view s) noexcept {
  for (const auto& [value, name] : table) {
    if (name == s) return value;
  }
  return std::nullopt;
}

}  // namespace

std::string_view effect_name(Effect e) noexcept { return name_of(kEffectNames, e); }
std::optional<Effect> effect_from_name(std::string_view s) noexcept {
  return value_of(kEffectNames, s);
}
std::string_view quality_name(Quality q) noexcept { return name_of(kQualityNames, q); }
std::optional<Quality> quality_from_name(std::string_view s) noexcept {
  return value_of(kQualityNames, s);
}
std::string_view solver_kind_name(SolverKind k) noexcept { return name_of(kSolverNames, k); }
std::optional<SolverKind> solver_kind_from_name(std::string_view s) noexcept {
  return value_of(kSolverNames, s);
}
std::string_view tool_kind_name(ToolKind k) noexcept { return name_of(kToolKindNames, k); }
std::optional<ToolKind> tool_kind_from_name(std::string_view s) noexcept {
  return value_of(kToolKindNames, s);
}
std::string_view device_kind_name(DeviceKind k) noexcept { return name_of(kDeviceNames, k); }
std::optional<DeviceKind> device_kind_from_name(std::string_view s) noexcept {
  return value_of(kDeviceNames, s);
}
std::string_view hand_name(Hand h) noexcept { return name_of(kHandNames, h); }
std::optional<Hand> hand_from_name(std::string_view s) noexcept { return value_of(kHandNames, s); }
std::string_view cut_method_name(CutMethod m) noexcept { return name_of(kCutMethodNames, m); }
std::optional<CutMethod> cut_method_from_name(std::string_view s) noexcept {
  return value_of(kCutMethodNames, s);
}
std::string_view stroke_surface_name(StrokeSurfaceKind k) noexcept {
  return name_of(kStrokeSurfaceNames, k);
}
std::optional<StrokeSurfaceKind> stroke_surface_from_name(std::string_view s) noexcept {
  return value_of(kStrokeSurfaceNames, s);
}
std::string_view surroundings_name(Surroundings s) noexcept {
  return name_of(kSurroundingsNames, s);
}
std::optional<Surroundings> surroundings_from_name(std::string_view s) noexcept {
  return value_of(kSurroundingsNames, s);
}

bool Box::contains(const Vec3& p) const {
  return (p.array() >= min_m.array()).all() && (p.array() <= max_m.array()).all();
}

bool OrganTransform::is_identity() const {
  return translate_m.isZero(0.0) && rotate_deg.isZero(0.0) && scale == 1.0;
}

Mat3 OrganTransform::rotation() const {
  const Vec3 r = rotate_deg * (std::numbers::pi / 180.0);
  const Mat3 rx = Eigen::AngleAxisd(r.x(), Vec3::UnitX()).toRotationMatrix();
  const Mat3 ry = Eigen::AngleAxisd(r.y(), Vec3::UnitY()).toRotationMatrix();
  const Mat3 rz = Eigen::AngleAxisd(r.z(), Vec3::UnitZ()).toRotationMatrix();
  return rz * ry * rx;
}

Vec3 OrganTransform::apply(const Vec3& p_mesh) const {
  return translate_m + rotation() * (scale * p_mesh);
}

const Material& Organ::material_for(int group) const {
  const auto it = group_materials.find(group);
  return it == group_materials.end() ? material : it->second;
}

std::optional<int> Organ::group_id(std::string_view group_name) const {
  for (const auto& [id, n] : groups) {
    if (n == group_name) return id;
  }
  return std::nullopt;
}

std::optional<std::size_t> Scene::tool_index(std::string_view name) const {
  for (std::size_t i = 0; i < tools.size(); ++i) {
    if (tools[i].name == name) return i;
  }
  return std::nullopt;
}

}  // namespace serosa
