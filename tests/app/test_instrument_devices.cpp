// One scene, every use: the shipped scene's scripted instruments go to the rig when it is plugged
// in and to the mouse otherwise in the window, the endoscope keeps its script, a scene that names
// a device keeps it, and --path replaces every script (app/instrument_devices.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/instrument_devices.h"
#include "app_test_util.h"
#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "engine/scene/tool_path.h"
#include "engine/scope_view.h"
#include "engine/tool_geometry.h"
#include "haptics/haptics_stage.h"
#include "haptics/trocar_kinematics.h"

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
  Scene scene = load_scene(source("config/transection.toml"));
  ASSERT_FALSE(scene.settings.has(Effect::kHaptics));
  const auto given = give_instruments_to_trainee(scene, false);
  ASSERT_TRUE(given.has_value());
  EXPECT_EQ(given->device, DeviceKind::kMouse);
  EXPECT_EQ(tool(scene, "grasper").device.kind, DeviceKind::kMouse);
  EXPECT_EQ(tool(scene, "scissors").device.kind, DeviceKind::kMouse);
  EXPECT_EQ(tool(scene, "endoscope").device.kind, DeviceKind::kMouse);  // the window's keys
  EXPECT_TRUE(scene.settings.has(Effect::kHaptics));
  // They start in the endoscope's view, at the first pose of their script (config/paths/
  // appendectomy.csv) in which the scope, as the script starts it, sees the tip and the shaft
  // behind it: each mouse handle's trocar axis points there, its rest pose puts the tip on it
  // and rolls its jaws into the script's jaw plane there.
  ASSERT_EQ(given->start_pose.size(), scene.tools.size());
  const ToolPath path = read_tool_path(source("config/paths/appendectomy.csv"));
  const ScopeView view = scope_view(sample(path, "endoscope", 0.0));
  const auto seen = [&view](const ToolState& s) {
    const ToolFrame f = tool_frame(s);
    return in_view(view, f.tip) && in_view(view, f.tip - 0.02 * f.forward) &&
           (f.tip - view.eye).norm() >= 0.04;
  };
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    const Tool& t = scene.tools[i];
    if (t.kind == ToolKind::kEndoscope) {
      EXPECT_FALSE(given->start_pose[i].has_value());
      // The scope is the trainee's too, from the script's first pose.
      EXPECT_EQ(t.device.kind, DeviceKind::kMouse);
      ASSERT_TRUE(given->scope_start[i].has_value());
      EXPECT_EQ(given->scope_start[i]->tip_m, sample(path, t.name, 0.0).tip_m);
      EXPECT_EQ(given->scope_start[i]->quat_wxyz, sample(path, t.name, 0.0).quat_wxyz);
      continue;
    }
    EXPECT_FALSE(given->scope_start[i].has_value()) << t.name;
    ASSERT_TRUE(given->start_pose[i].has_value()) << t.name;
    const ToolState& start = *given->start_pose[i];
    EXPECT_TRUE(seen(start)) << t.name;
    bool earlier = false;
    for (double s = 0.0; s + 1e-9 < start.time_s; s += 0.05)
      earlier = earlier || seen(sample(path, t.name, s));
    EXPECT_FALSE(earlier) << t.name;
    const Vec3 tip(start.tip_m[0], start.tip_m[1], start.tip_m[2]);
    const haptics::MouseHandle mh = haptics::mouse_handle(t, i % 2, Vec3::Zero(), start);
    const ToolState rest = haptics::forward(mh.trocar, mh.rest);
    EXPECT_LT((Vec3(rest.tip_m[0], rest.tip_m[1], rest.tip_m[2]) - tip).norm(), 1e-12) << t.name;
    // The jaw planes' normals agree as far as the shafts do.
    const ToolFrame want = tool_frame(start), got = tool_frame(rest);
    EXPECT_GE(want.pin.dot(got.pin), want.forward.dot(got.forward) - 1e-9) << t.name;
  }
  // The scene composes as written: the loop's handles are the grasper and the scissors, driven
  // by the mouse; no script plays (the window poses the endoscope).
  AssembledScene assembled = assemble_state(scene);
  ComposeOptions options;
  options.mouse_rest_pose = given->start_pose;
  const Composition comp = compose(scene, assembled, std::move(options));
  ASSERT_NE(comp.haptics, nullptr);
  EXPECT_EQ(comp.haptics->device_kind(), DeviceKind::kMouse);
  ASSERT_TRUE(comp.haptics->handle_tools()[0].has_value());
  ASSERT_TRUE(comp.haptics->handle_tools()[1].has_value());
  EXPECT_EQ(comp.tools, nullptr);
}

// Every shipped scene hands its instruments over where the endoscope sees them: each starts at a
// pose its script reaches in which the scope, as its script starts it, sees the tip and the
// shaft behind it, 4 cm or more from the lens (every shipped script brings each instrument into
// view at some time).
TEST(InstrumentDevices, EveryShippedSceneStartsItsInstrumentsInView) {
  int checked = 0;
  for (auto& [file, scene] : testing::shipped_scenes()) {
    const auto given = give_instruments_to_trainee(scene, false);
    if (!given) continue;
    std::optional<ToolState> scope;
    for (const auto& st : given->scope_start)
      if (st) scope = st;
    if (!scope) continue;
    const ScopeView view = scope_view(*scope);
    for (std::size_t i = 0; i < scene.tools.size(); ++i) {
      if (!given->start_pose[i]) continue;
      const ToolFrame f = tool_frame(*given->start_pose[i]);
      EXPECT_TRUE(in_view(view, f.tip) && in_view(view, f.tip - 0.02 * f.forward) &&
                  (f.tip - view.eye).norm() >= 0.04)
          << file << " " << scene.tools[i].name;
      ++checked;
    }
  }
  EXPECT_GE(checked, 10);
}

TEST(InstrumentDevices, ARigPluggedInTakesTheInstruments) {
  Scene scene = load_scene(source("config/transection.toml"));
  const auto given = give_instruments_to_trainee(scene, true);
  ASSERT_TRUE(given.has_value());
  EXPECT_EQ(given->device, DeviceKind::kRig);
  EXPECT_EQ(tool(scene, "grasper").device.kind, DeviceKind::kRig);
  EXPECT_EQ(tool(scene, "scissors").device.kind, DeviceKind::kRig);
  EXPECT_EQ(tool(scene, "endoscope").device.kind, DeviceKind::kMouse);  // the rig has 2 handles
  EXPECT_TRUE(scene.settings.has(Effect::kHaptics));
}

TEST(InstrumentDevices, ASceneThatNamesADeviceKeepsIt) {
  Scene scene = load_scene(source("config/transection.toml"));
  for (Tool& t : scene.tools)
    if (t.name == "grasper") t.device.kind = DeviceKind::kRigEmulated;
  const Scene before = scene;
  EXPECT_FALSE(give_instruments_to_trainee(scene, false).has_value());
  EXPECT_EQ(tool(scene, "scissors").device.kind, DeviceKind::kScript);
  EXPECT_EQ(tool(scene, "grasper").device.kind, DeviceKind::kRigEmulated);
  EXPECT_EQ(scene.settings.effects, before.settings.effects);
  // Nothing scripted but the camera: nothing to give.
  Scene camera_only = load_scene(source("config/transection.toml"));
  std::erase_if(camera_only.tools, [](const Tool& t) { return t.kind != ToolKind::kEndoscope; });
  EXPECT_FALSE(give_instruments_to_trainee(camera_only, true).has_value());
  EXPECT_FALSE(camera_only.settings.has(Effect::kHaptics));
}

TEST(InstrumentDevices, APathReplacesEveryScriptAndAMissingOneIsAnError) {
  Scene scene = load_scene(source("config/transection.toml"));
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
