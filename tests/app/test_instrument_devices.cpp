// One scene, every use: the shipped scene's scripted instruments go to the rig when it is plugged
// in and to the mouse otherwise in the window, the endoscope keeps its script, a scene that names
// a device keeps it, and --path replaces every script (app/instrument_devices.h).
#include <gtest/gtest.h>

#include <algorithm>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/instrument_devices.h"
#include "app_test_util.h"
#include "engine/input_error.h"
#include "engine/scene.h"
#include "haptics/haptics_stage.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

const Tool& tool(const Scene& s, const std::string& name) {
  const auto it =
      std::find_if(s.tools.begin(), s.tools.end(), [&](const Tool& t) { return t.name == name; });
  EXPECT_NE(it, s.tools.end()) << name;
  return *it;
}

TEST(InstrumentDevices, TheDefaultSceneGoesToTheMouseWithoutARig) {
  Scene scene = load_scene(source("config/appendectomy.toml"));
  ASSERT_FALSE(scene.settings.has(Effect::kHaptics));
  const auto device = give_instruments_to_trainee(scene, false);
  ASSERT_EQ(device, DeviceKind::kMouse);
  EXPECT_EQ(tool(scene, "grasper").device.kind, DeviceKind::kMouse);
  EXPECT_EQ(tool(scene, "scissors").device.kind, DeviceKind::kMouse);
  EXPECT_EQ(tool(scene, "endoscope").device.kind, DeviceKind::kScript);  // the camera plays on
  EXPECT_TRUE(scene.settings.has(Effect::kHaptics));
  // The scene composes as written: the loop's handles are the grasper and the scissors, driven
  // by the mouse, and the endoscope's script still plays.
  AssembledScene assembled = assemble_state(scene);
  const Composition comp = compose(scene, assembled);
  ASSERT_NE(comp.haptics, nullptr);
  EXPECT_EQ(comp.haptics->device_kind(), DeviceKind::kMouse);
  ASSERT_TRUE(comp.haptics->handle_tools()[0].has_value());
  ASSERT_TRUE(comp.haptics->handle_tools()[1].has_value());
  EXPECT_NE(comp.tools, nullptr);
}

TEST(InstrumentDevices, ARigPluggedInTakesTheInstruments) {
  Scene scene = load_scene(source("config/appendectomy.toml"));
  EXPECT_EQ(give_instruments_to_trainee(scene, true), DeviceKind::kRig);
  EXPECT_EQ(tool(scene, "grasper").device.kind, DeviceKind::kRig);
  EXPECT_EQ(tool(scene, "scissors").device.kind, DeviceKind::kRig);
  EXPECT_EQ(tool(scene, "endoscope").device.kind, DeviceKind::kScript);
  EXPECT_TRUE(scene.settings.has(Effect::kHaptics));
}

TEST(InstrumentDevices, ASceneThatNamesADeviceKeepsIt) {
  Scene scene = load_scene(source("config/appendectomy.toml"));
  for (Tool& t : scene.tools)
    if (t.name == "grasper") t.device.kind = DeviceKind::kRigEmulated;
  const Scene before = scene;
  EXPECT_EQ(give_instruments_to_trainee(scene, false), std::nullopt);
  EXPECT_EQ(tool(scene, "scissors").device.kind, DeviceKind::kScript);
  EXPECT_EQ(tool(scene, "grasper").device.kind, DeviceKind::kRigEmulated);
  EXPECT_EQ(scene.settings.effects, before.settings.effects);
  // Nothing scripted but the camera: nothing to give.
  Scene camera_only = load_scene(source("config/appendectomy.toml"));
  std::erase_if(camera_only.tools, [](const Tool& t) { return t.kind != ToolKind::kEndoscope; });
  EXPECT_EQ(give_instruments_to_trainee(camera_only, true), std::nullopt);
  EXPECT_FALSE(camera_only.settings.has(Effect::kHaptics));
}

TEST(InstrumentDevices, APathReplacesEveryScriptAndAMissingOneIsAnError) {
  Scene scene = load_scene(source("config/appendectomy.toml"));
  const fs::path csv = source("config/paths/appendix_transection.csv");
  play_tool_path(scene, csv);
  for (const Tool& t : scene.tools) {
    EXPECT_EQ(t.device.kind, DeviceKind::kScript) << t.name;
    EXPECT_EQ(t.device.script, csv) << t.name;
  }
  try {
    play_tool_path(scene, source("config/paths/no_such_path.csv"));
    FAIL() << "a missing tool path must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_path.csv"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace serosa::app
