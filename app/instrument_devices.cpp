#include "app/instrument_devices.h"

#include <algorithm>

#include "engine/input_error.h"
#include "engine/tool_path.h"

namespace serosa::app {

void play_tool_path(Scene& scene, const std::filesystem::path& csv) {
  if (!std::filesystem::exists(csv)) throw InputError(csv.string(), 0, "tool path file not found");
  for (Tool& t : scene.tools) {
    const bool emulated_rig_plays =
        t.device.kind == DeviceKind::kRigEmulated && !t.device.script.empty();
    if (t.device.kind == DeviceKind::kScript || emulated_rig_plays) t.device.script = csv;
  }
}

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
  given.start_tip_m.resize(scene.tools.size());
  given.scope_start.resize(scene.tools.size());
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    Tool& t = scene.tools[i];
    if (!scripted(t)) continue;
    const ToolPath path = read_tool_path(t.device.script);  // the loader read it: it parses
    std::optional<ToolState> start;
    if (path.index_of(t.name)) start = sample(path, t.name, 0.0);
    if (instrument(t)) {
      if (start) given.start_tip_m[i] = Vec3(start->tip_m[0], start->tip_m[1], start->tip_m[2]);
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
