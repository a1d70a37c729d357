// Which device drives a scene's instruments in each use. A scene names one device per tool; the
// shipped scenes script theirs (the procedure, played headless), and the same scene is the
// trainee's in a window:
//  - `--path FILE` (headless and run): every scripted tool plays FILE instead of its own path,
//    and so do the emulated rig's handles (device "rig-emulated:FILE");
//  - `serosa run` without it: the scripted graspers and scissors follow the rig when one is
//    plugged in, else the mouse and keyboard, through the haptic loop (the "haptics" effect is
//    added: the loop is what reads a device); the scripted endoscope follows the window's keys
//    and right button (window/scope_control.h; the rig has no third handle), from where its script
//    starts it. A scene that already drives an instrument by a device (rig, rig-emulated or
//    mouse) keeps the devices it names;
//  - `serosa headless`: the devices the scene names.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include "engine/scene/scene.h"
#include "engine/tool_state.h"

namespace serosa::app {

/// Every scripted tool of `scene`, and every emulated rig handle that plays a path, plays the
/// tool path `csv`. Throws InputError naming the file
/// when it does not exist.
void play_tool_path(Scene& scene, const std::filesystem::path& csv);

/// The instruments handed to the trainee.
struct TraineeInstruments {
  DeviceKind device = DeviceKind::kMouse;  ///< rig or mouse
  /// (tools) Where each handed-over instrument rests at the start, m: the first pose of its
  /// script in which the endoscope, as its script starts it, sees the tip and the shaft behind
  /// it, 4 cm or more from the lens (else where its script starts it; nullopt for the others, and
  /// for a tool its script does not name): mouse handles rest there
  /// (ComposeOptions::mouse_rest_pose), their blades turned as the script turns them there.
  std::vector<std::optional<ToolState>> start_pose;
  /// (tools) The handed-over endoscope's first scripted pose (nullopt for the other tools): the
  /// trainee's scope starts there.
  std::vector<std::optional<ToolState>> scope_start;
};

/// Hands the scene's scripted instruments to the trainee (above): to the rig when
/// `rig_plugged_in`, else to the mouse. Returns what they were given, or nullopt when the
/// scene's own devices stand (an instrument already driven by a device, or none scripted).
std::optional<TraineeInstruments> give_instruments_to_trainee(Scene& scene, bool rig_plugged_in);

}  // namespace serosa::app
