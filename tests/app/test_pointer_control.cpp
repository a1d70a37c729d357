// The mouse as a trainee uses it (window/pointer_control.h): drags move the tip the way the pointer
// goes in the picture at one gain however far the instrument is in, J's taps and holds work the
// jaws, Tab changes hands.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "app/instrument_devices.h"
#include "app_test_util.h"
#include "engine/jaw_range.h"
#include "engine/scene/scene.h"
#include "engine/scope_view.h"
#include "haptics/haptics_stage.h"
#include "haptics/mouse_device.h"
#include "render/camera.h"
#include "window/pointer_control.h"
#include "window/window_pointer.h"

namespace serosa::app {
namespace {

using testing::source;

Vec3 tip_of(const ToolState& t) { return {t.tip_m[0], t.tip_m[1], t.tip_m[2]}; }

// Pixel position of p in a width x height picture of `cam` (origin top left).
Eigen::Vector2d project(const render::Camera& cam, const Vec3& p, int width, int height) {
  render::Bounds b;
  b.lo = Eigen::Vector3f(-0.3f, -0.3f, -0.3f);
  b.hi = Eigen::Vector3f(0.3f, 0.3f, 0.3f);
  b.empty = false;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const render::CameraMatrices m = render::camera_matrices(cam, aspect, b);
  const Eigen::Vector4f c =
      m.projection * m.view *
      Eigen::Vector4f(p.cast<float>().x(), p.cast<float>().y(), p.cast<float>().z(), 1.0f);
  const double x = static_cast<double>(c.x() / c.w());
  const double y = static_cast<double>(c.y() / c.w());
  return {(0.5 * x + 0.5) * width, (0.5 - 0.5 * y) * height};
}

// Every instrument of the shipped scenes, resting where serosa run puts it (its trocar, in the
// endoscope's first view): a drag of 100 px to the right moves its tip 1 cm along the picture's
// right, so the picture shows it moving right and not up or down; the same after retracting it
// 3 cm and after inserting it 3 cm.
TEST(PointerControl, ADragRightMovesEveryTipRightOnScreenAtOneGain) {
  for (const char* file : {"config/transection.toml", "config/appendectomy.toml"}) {
    Scene scene = load_scene(source(file));
    const auto given = give_instruments_to_trainee(scene, false);
    ASSERT_TRUE(given.has_value()) << file;
    std::optional<ToolState> scope;
    for (const auto& s : given->scope_start)
      if (s) scope = s;
    ASSERT_TRUE(scope.has_value()) << file;
    const render::Camera cam = render::endoscope_camera(
        {static_cast<float>(scope->tip_m[0]), static_cast<float>(scope->tip_m[1]),
         static_cast<float>(scope->tip_m[2])},
        {static_cast<float>(scope->quat_wxyz[0]), static_cast<float>(scope->quat_wxyz[1]),
         static_cast<float>(scope->quat_wxyz[2]), static_cast<float>(scope->quat_wxyz[3])},
        static_cast<float>(scope_angle_deg(*scope)), static_cast<float>(kScopeFovDeg));
    const window::ScreenAxes axes = window::screen_axes(cam);
    int checked = 0;
    for (std::size_t i = 0; i < scene.tools.size(); ++i) {
      const Tool& t = scene.tools[i];
      if (t.kind == ToolKind::kEndoscope) continue;
      ASSERT_TRUE(given->start_pose[i].has_value()) << file << " " << t.name;
      const haptics::MouseHandle mh =
          haptics::mouse_handle(t, 0, Vec3::Zero(), given->start_pose[i]);
      haptics::MouseMapping map;
      map.ease_s = 0.0;
      map.rest[0] = mh.rest;
      haptics::MouseKeyboardDevice dev({mh.trocar, mh.trocar}, map);
      window::PointerControl pointer;
      haptics::DeviceSample s;
      double now = 0.0;
      ASSERT_TRUE(dev.poll(now, s));
      for (const double depth : {0.0, -10.0, 20.0}) {  // as it rests, 3 cm out, 3 cm in
        window::PointerEvents e;
        e.scroll_steps = depth;  // the wheel: along the shaft
        dev.feed(pointer.update(e, axes));
        ASSERT_TRUE(dev.poll(now += 0.1, s));
        const Vec3 before = tip_of(s.pose[0]);
        window::PointerEvents drag;
        drag.drag_dx_px = 100.0;
        dev.feed(pointer.update(drag, axes));
        ASSERT_TRUE(dev.poll(now += 0.1, s));
        const Vec3 moved = tip_of(s.pose[0]) - before;
        EXPECT_NEAR(moved.norm(), 100.0 * window::kDragMetresPerPixel, 1e-9)
            << t.name << " " << depth;
        EXPECT_NEAR(moved.normalized().dot(axes.right), 1.0, 1e-9) << t.name << " " << depth;
        const Eigen::Vector2d a = project(cam, before, 1280, 720);
        const Eigen::Vector2d b = project(cam, tip_of(s.pose[0]), 1280, 720);
        EXPECT_GT(b.x() - a.x(), 5.0) << t.name << " " << depth;
        EXPECT_LT(std::abs(b.y() - a.y()), 0.05 * (b.x() - a.x())) << t.name << " " << depth;
        ++checked;
      }
    }
    EXPECT_GE(checked, 6) << file;
  }
}

// J: a tap opens closed jaws fully and closes open ones; held, it closes them steadily from
// where they were, and they stay where they are when let go. A tap is told by how long the key
// was surely down (render/key_clock.h): one that went down and up between two frames, or across
// a frame however slow, still counts as a tap.
TEST(PointerControl, JawsTapToToggleHoldToBite) {
  window::PointerControl p;
  const window::ScreenAxes axes;
  window::PointerEvents tap;
  tap.jaw_presses = 1;  // down and up between two frames
  tap.jaw_released_after_s = 0.02;
  EXPECT_EQ(p.update(tap, axes).jaw_fraction[0], 1.0);
  EXPECT_EQ(p.update(tap, axes).jaw_fraction[0], 0.0);
  EXPECT_EQ(p.update(tap, axes).jaw_fraction[0], 1.0);
  // Down for 1.15 s over frames, then let go: closing from 0.25 s on at 1 / kJawCloseS.
  window::PointerEvents down;
  down.jaw_presses = 1;
  down.jaw_held = true;
  down.jaw_held_s = 0.01;
  window::PointerEvents held;
  held.jaw_held = true;
  const auto held_for = [&](double s) {
    held.jaw_held_s = s;
    return held;
  };
  window::PointerEvents up;
  up.jaw_released_after_s = 1.15;
  EXPECT_EQ(p.update(down, axes).jaw_fraction[0], 1.0);
  EXPECT_EQ(p.update(held_for(0.2), axes).jaw_fraction[0], 1.0);  // could still be a tap
  EXPECT_NEAR(p.update(held_for(0.85), axes).jaw_fraction[0], 1.0 - 0.6 / window::kJawCloseS,
              1e-12);
  const double bitten = 1.0 - 0.9 / window::kJawCloseS;
  EXPECT_NEAR(p.update(up, axes).jaw_fraction[0], bitten, 1e-12);  // at the release's time
  EXPECT_NEAR(p.update(window::PointerEvents{}, axes).jaw_fraction[0], bitten, 1e-12);
  // Held long enough, they close fully and no further.
  EXPECT_NEAR(p.update(down, axes).jaw_fraction[0], bitten, 1e-12);
  EXPECT_EQ(p.update(held_for(10.0), axes).jaw_fraction[0], 0.0);
  up.jaw_released_after_s = 10.1;
  EXPECT_EQ(p.update(up, axes).jaw_fraction[0], 0.0);
  // A tap on jaws at most half open opens them.
  EXPECT_EQ(p.update(window::PointerEvents{}, axes).jaw_fraction[0], 0.0);
  EXPECT_EQ(p.update(tap, axes).jaw_fraction[0], 1.0);
  // A tap whose press a frame saw and whose release came after a 0.5 s frame is still a tap:
  // the frames' times do not stretch it into a bite.
  down.jaw_held_s = 0.05;
  EXPECT_EQ(p.update(down, axes).jaw_fraction[0], 1.0);
  up.jaw_released_after_s = 0.08;
  EXPECT_EQ(p.update(up, axes).jaw_fraction[0], 0.0);
}

// Each hand keeps its own input; Tab changes which one the events go to, and nothing the window
// gathered is lost however slow the frames.
TEST(PointerControl, TabSwitchesHandsAndEveryEventCounts) {
  window::PointerControl p;
  window::ScreenAxes axes;
  window::PointerEvents e;
  e.drag_dx_px = 30.0;
  e.drag_dy_px = 10.0;
  e.insert = 3;
  e.retract = 1;
  e.scroll_steps = 2.0;
  e.roll_right = 2;
  e.pedal = 1;
  e.home = 1;
  haptics::PointerInput in = p.update(e, axes);
  EXPECT_NEAR(in.move_m[0][0], 30.0 * window::kDragMetresPerPixel, 1e-15);
  EXPECT_NEAR(in.move_m[0][1], -10.0 * window::kDragMetresPerPixel, 1e-15);  // down the picture
  EXPECT_EQ(in.depth_steps[0], 2.0);                                         // the wheel
  EXPECT_NEAR(in.move_m[0][2], -2.0 * window::kDepthMetresPerStep, 1e-15);  // W/S: into the picture
  EXPECT_EQ(in.roll_steps[0], 2.0);
  EXPECT_NE(in.buttons[0], 0u);
  EXPECT_EQ(in.homes[0], 1u);
  window::PointerEvents tab;
  tab.tab = 1;
  tab.drag_dx_px = 5.0;
  in = p.update(tab, axes);
  EXPECT_EQ(p.active(), 1u);
  EXPECT_NEAR(in.move_m[1][0], 5.0 * window::kDragMetresPerPixel, 1e-15);
  EXPECT_NEAR(in.move_m[0][0], 30.0 * window::kDragMetresPerPixel, 1e-15);
  tab.drag_dx_px = 0.0;
  tab.tab = 2;  // two presses in one frame: back where it was
  (void)p.update(tab, axes);
  EXPECT_EQ(p.active(), 1u);
}

}  // namespace
}  // namespace serosa::app
