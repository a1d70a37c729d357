#include "app/instrument_devices.h"

#include <algorithm>

#include "engine/input_error.h"
#include "engine/scene/tool_path.h"
#include "engine/scope_view.h"
#include "engine/tool_geometry.h"

namespace serosa::app {

void play_tool_path(Scene& scene, const std::filesystem::path& csv) {
  if (!std::filesystem::exists(csv)) throw InputError(csv.string(), 0, "tool path file not found");
  for (Tool& t : scene.tools) {
    const bool emulated_rig_plays =
        t.device.kind == DeviceKind::kRigEmulated && !t.device.script.empty();
    if (t.device.kind == DeviceKind::kScript || emulated_rig_plays) t.device.script = csv;
  }
}

namespace {

// Where a handed-over instrument rests at the start: the first pose of its script (sampled every
// kScanS) whose tip and the shaft just behind it the scope sees from where its script starts it,
// at least kNearestM from the lens, so the trainee sees what they hold; else its script's first
// pose.
constexpr double kScanS = 0.05;
constexpr double kShaftSeenM = 0.02;  // this much of the shaft behind the tip in view too, m
constexpr double kNearestM = 0.04;    // nearer, it fills the picture, m

std::optional<ToolState> first_in_view(const ToolPath& path, const std::string& tool,
                                       const std::optional<ToolState>& scope) {
  if (!path.index_of(tool)) return std::nullopt;
  const ToolState start = sample(path, tool, 0.0);
  if (!scope || !scope_posed(*scope)) return start;
  const ScopeView view = scope_view(*scope);
  for (double t = 0.0; t <= path.end_time_s(); t += kScanS) {
    const ToolState s = sample(path, tool, t);
    const ToolFrame f = tool_frame(s);
    if (in_view(view, f.tip) && in_view(view, f.tip - kShaftSeenM * f.forward) &&
        (f.tip - view.eye).norm() >= kNearestM)
      return s;
  }
  return start;
}

}  // namespace

std::optional<TraineeInstruments> give_instruments_to_trainee(Scene& scene, bool rig_plugged_in) {
  const auto instrument = [](const Tool& t) { return t.kind != ToolKind::kEndoscope; };
  const auto scripted = [](const Tool& t) { return t.device.kind == DeviceKind::kScript; };
  const bool chosen = std::any_of(scene.tools.begin(), scene.tools.end(),
                                  [&](const Tool& t) { return instrument(t) && !scripted(t); });
  const bool any = std::any_of(scene.tools.begin(), scene.tools.end(),
                               [&](const Tool& t) { return instrument(t) && scripted(t); });
  if (chosen || !any) return std::nullopt;
  TraineeInstruments given;
  given.device = rig_plugged_in ? DeviceKind::kRig : DeviceKind::kMouse;
  given.start_pose.resize(scene.tools.size());
  given.scope_start.resize(scene.tools.size());
  // The scope first: the instruments start where it sees them.
  std::optional<ToolState> scope;
  for (const Tool& t : scene.tools) {
    if (instrument(t) || !scripted(t) || scope) continue;
    const ToolPath path = read_tool_path(t.device.script);
    if (path.index_of(t.name)) scope = sample(path, t.name, 0.0);
  }
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    Tool& t = scene.tools[i];
    if (!scripted(t)) continue;
    const ToolPath path = read_tool_path(t.device.script);  // the loader read it: it parses
    std::optional<ToolState> start;
    if (instrument(t))
      start = first_in_view(path, t.name, scope);
    else if (path.index_of(t.name))
      start = sample(path, t.name, 0.0);
    if (instrument(t)) {
      given.start_pose[i] = start;
      t.device.kind = given.device;
    } else {
      if (!start) continue;  // an endoscope its script does not pose keeps the script
      given.scope_start[i] = start;
      t.device.kind = DeviceKind::kMouse;  // the window's keys and right button
    }
    t.device.script.clear();
  }
  scene.settings.effects.insert(Effect::kHaptics);
  return given;
}

}  // namespace serosa::app
