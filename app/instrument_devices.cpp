#include "app/instrument_devices.h"

#include <algorithm>

#include "engine/input_error.h"

namespace serosa::app {

void play_tool_path(Scene& scene, const std::filesystem::path& csv) {
  if (!std::filesystem::exists(csv)) throw InputError(csv.string(), 0, "tool path file not found");
  for (Tool& t : scene.tools)
    if (t.device.kind == DeviceKind::kScript) t.device.script = csv;
}

std::optional<DeviceKind> give_instruments_to_trainee(Scene& scene, bool rig_plugged_in) {
  const auto instrument = [](const Tool& t) { return t.kind != ToolKind::kEndoscope; };
  const auto scripted = [](const Tool& t) { return t.device.kind == DeviceKind::kScript; };
  const bool chosen = std::any_of(scene.tools.begin(), scene.tools.end(),
                                  [&](const Tool& t) { return instrument(t) && !scripted(t); });
  const bool any = std::any_of(scene.tools.begin(), scene.tools.end(),
                               [&](const Tool& t) { return instrument(t) && scripted(t); });
  if (chosen || !any) return std::nullopt;
  const DeviceKind device = rig_plugged_in ? DeviceKind::kRig : DeviceKind::kMouse;
  for (Tool& t : scene.tools) {
    if (!instrument(t)) continue;
    t.device.kind = device;
    t.device.script.clear();
  }
  scene.settings.effects.insert(Effect::kHaptics);
  return device;
}

}  // namespace serosa::app
