// The ImGui overlay through EGL: it draws its panels where it says, shows the replay timeline
// only in replays, and turns clicks on its controls into actions (pause, seek, view). Pictures
// go to <build>/test-output/render/.
#include <gtest/gtest.h>

#include <memory>

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/overlay.h"
#include "render/png_writer.h"
#include "render/render_fixtures.h"

namespace serosa::render {
namespace {

class OverlayTest : public ::testing::Test {
 protected:
  static constexpr int kW = 480;
  static constexpr int kH = 320;
  void SetUp() override {
    try {
      ctx_ = std::make_unique<OffscreenContext>(kW, kH);
      fixtures::pin_gl_driver();
      renderer_ = std::make_unique<FrameRenderer>();
      overlay_ = std::make_unique<Overlay>();
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
    frame_ = fixtures::frame_of(fixtures::icosphere(2, 0.02f));
    frame_.group_names = {"", "appendix"};
    options_.width = kW;
    options_.height = kH;
    options_.fit_camera = true;
  }
  void TearDown() override {
    overlay_.reset();
    renderer_.reset();
    ctx_.reset();
  }

  // Draws the frame and, when `data` is given, the overlay over it; reads the picture back.
  Image shoot(const OverlayData* data, const OverlayInput& input, OverlayResult* result,
              const char* png) {
    ctx_->bind_framebuffer();
    renderer_->draw(frame_, options_, kW, kH);
    if (data != nullptr) {
      const OverlayResult r = overlay_->draw(*data, options_, kW, kH, input);
      if (result != nullptr) *result = r;
    }
    Image img = ctx_->read_image();
    if (png != nullptr) write_png(img, fixtures::output_path(png));
    return img;
  }

  // Pixels inside `rect` (x0, y0, x1, y1) whose colour differs by more than 24 in some channel.
  static std::size_t changed_in(const Image& a, const Image& b, const std::array<float, 4>& r) {
    std::size_t n = 0;
    for (int y = std::max(0, static_cast<int>(r[1])); y < std::min(kH, static_cast<int>(r[3]));
         ++y) {
      for (int x = std::max(0, static_cast<int>(r[0])); x < std::min(kW, static_cast<int>(r[2]));
           ++x) {
        const auto p = a.at(x, y);
        const auto q = b.at(x, y);
        for (int k = 0; k < 3; ++k) {
          if (std::abs(p[k] - q[k]) > 24) {
            ++n;
            break;
          }
        }
      }
    }
    return n;
  }

  std::unique_ptr<OffscreenContext> ctx_;
  std::unique_ptr<FrameRenderer> renderer_;
  std::unique_ptr<Overlay> overlay_;
  RenderFrame frame_;
  SnapshotOptions options_;
};

TEST_F(OverlayTest, StatisticsPanelAndReplayTimelineShowWhereTheySay) {
  const Image plain = shoot(nullptr, {}, nullptr, "overlay_none.png");
  OverlayData d;
  d.sim_time_s = 12.5;
  d.fem_ms_per_step = 3.2;
  d.solver_rate_hz = 200.0;
  d.cuts = 2;
  OverlayResult r;
  const Image stats = shoot(&d, {}, &r, "overlay_stats.png");
  // A panel of a sensible size in the top left, with text and background drawn into it.
  EXPECT_LT(r.stats_rect[0], 20.0f);
  EXPECT_LT(r.stats_rect[1], 20.0f);
  EXPECT_GT(r.stats_rect[2] - r.stats_rect[0], 100.0f);
  EXPECT_GT(r.stats_rect[3] - r.stats_rect[1], 50.0f);
  const double area = static_cast<double>(r.stats_rect[2] - r.stats_rect[0]) *
                      static_cast<double>(r.stats_rect[3] - r.stats_rect[1]);
  const std::size_t in_panel = changed_in(plain, stats, r.stats_rect);
  EXPECT_GT(static_cast<double>(in_panel), 0.2 * area);
  // Outside it nothing changed.
  const std::array<float, 4> rest{r.stats_rect[2] + 2.0f, 0.0f, static_cast<float>(kW),
                                  static_cast<float>(kH)};
  EXPECT_EQ(changed_in(plain, stats, rest), 0u);
  // No timeline outside replays.
  EXPECT_EQ(r.timeline[2], 0.0f);

  d.replay = true;
  d.replay_duration_s = 60.0;
  d.replay_position_s = 15.0;
  const Image replay = shoot(&d, {}, &r, "overlay_replay.png");
  ASSERT_GT(r.timeline[2], r.timeline[0] + 200.0f);  // spans most of the width
  EXPECT_GT(r.timeline[1], 0.7f * kH);               // along the bottom
  EXPECT_GT(changed_in(plain, replay, r.timeline), 1000u);
  EXPECT_GT(r.pause_button[2], r.pause_button[0]);
  // Instructor metrics make the panel taller, one line each.
  const float plain_height = r.stats_rect[3] - r.stats_rect[1];
  d.metrics = {{"max force", 1.8, "N"}, {"cut length", 0.012, "m"}, {"contact time", 3.5, "s"}};
  shoot(&d, {}, &r, nullptr);  // an auto-sized panel takes its new size on the next frame
  const Image metrics = shoot(&d, {}, &r, "overlay_metrics.png");
  EXPECT_GT(r.stats_rect[3] - r.stats_rect[1], plain_height + 3 * 10.0f);
  EXPECT_GT(changed_in(replay, metrics, r.stats_rect), 200u);
  // Hidden: nothing drawn.
  d.visible = false;
  const Image hidden = shoot(&d, {}, &r, nullptr);
  EXPECT_EQ(changed_in(plain, hidden, {0.0f, 0.0f, kW, kH}), 0u);
}

TEST_F(OverlayTest, ClicksBecomeActions) {
  OverlayData d;
  d.replay = true;
  d.replay_duration_s = 40.0;
  d.replay_position_s = 10.0;
  OverlayResult r;
  shoot(&d, {}, &r, nullptr);  // lay out once to learn where the controls are
  const auto centre = [](const std::array<float, 4>& rect) {
    return std::array<float, 2>{0.5f * (rect[0] + rect[2]), 0.5f * (rect[1] + rect[3])};
  };
  // Pause: press and release on the button.
  const auto pb = centre(r.pause_button);
  OverlayInput in;
  in.mouse_x = pb[0];
  in.mouse_y = pb[1];
  shoot(&d, in, &r, nullptr);  // hover
  in.mouse_down = true;
  shoot(&d, in, &r, nullptr);
  EXPECT_FALSE(r.toggle_pause);
  EXPECT_TRUE(r.wants_mouse);
  in.mouse_down = false;
  shoot(&d, in, &r, nullptr);
  EXPECT_TRUE(r.toggle_pause);

  // Seek: press at three quarters of the timeline.
  const float x = r.timeline[0] + 0.75f * (r.timeline[2] - r.timeline[0]);
  in.mouse_x = x;
  in.mouse_y = centre(r.timeline)[1];
  shoot(&d, in, &r, nullptr);
  in.mouse_down = true;
  shoot(&d, in, &r, nullptr);
  ASSERT_TRUE(r.seek_s.has_value());
  EXPECT_NEAR(*r.seek_s, 30.0, 2.0);
  in.mouse_down = false;
  shoot(&d, in, &r, nullptr);

  // Away from the overlay the pointer is the scene's.
  in.mouse_x = 0.5f * kW;
  in.mouse_y = 0.4f * kH;
  shoot(&d, in, &r, nullptr);
  EXPECT_FALSE(r.wants_mouse);
  EXPECT_FALSE(r.toggle_pause);
  EXPECT_FALSE(r.seek_s.has_value());
}

}  // namespace
}  // namespace serosa::render

namespace serosa::render {
namespace {

// The overlay's text comes from the frame's statistics (no GL involved).
TEST(OverlayText, StatisticsLinesComeFromTheFrameStats) {
  OverlayData d;
  d.sim_time_s = 12.5;
  d.fem_ms_per_step = 3.25;
  d.solver_rate_hz = 199.6;
  d.cuts = 3;
  OverlayText t = overlay_text(d);
  ASSERT_EQ(t.stats.size(), 4u);
  EXPECT_EQ(t.stats[0], "t = 12.50 s");
  EXPECT_EQ(t.stats[1], "FEM 3.25 ms/step  (200 steps/s)");
  EXPECT_EQ(t.stats[2], "haptics \u2014");  // no haptic loop
  EXPECT_EQ(t.stats[3], "cuts 3");
  EXPECT_TRUE(t.timeline.empty());  // not a replay

  d.haptic_rate_hz = 998.7;
  d.paused = true;
  d.slow_motion = true;
  d.metrics = {{"max force", 1.8, "N"}, {"path length", 0.1234, "m"}, {"cuts made", 2.0, ""}};
  t = overlay_text(d);
  ASSERT_EQ(t.stats.size(), 7u);
  EXPECT_EQ(t.stats[0], "t = 12.50 s  [paused]  [slow motion]");
  EXPECT_EQ(t.stats[2], "haptics 999 Hz");
  EXPECT_EQ(t.stats[4], "max force 1.8 N");
  EXPECT_EQ(t.stats[5], "path length 0.123 m");
  EXPECT_EQ(t.stats[6], "cuts made 2");
}

TEST(OverlayText, ReplayTimelineShowsPositionDurationSpeedAndPause) {
  OverlayData d;
  d.replay = true;
  d.replay_position_s = 75.25;
  d.replay_duration_s = 130.0;
  d.replay_speed = 0.5;
  EXPECT_EQ(overlay_text(d).timeline, "1:15.2 / 2:10.0  x0.5");
  d.paused = true;
  d.replay_speed = 2.0;
  d.replay_position_s = -1.0;  // clamped to the start
  EXPECT_EQ(overlay_text(d).timeline, "0:00.0 / 2:10.0  x2  [paused]");
}

// The errors line says how far the assessment has got, how many errors and which keys reach
// them; a branch's clock and errors are its own.
TEST(OverlayText, TheErrorsLineAndABranchsClock) {
  OverlayData d;
  d.replay = true;
  d.replay_duration_s = 14.1;
  EXPECT_EQ(overlay_text(d).errors.rfind("assessing the recording", 0), 0u);
  d.timeline.done = true;
  EXPECT_EQ(overlay_text(d).errors, "no errors: every criterion passed");
  d.timeline.marks = {
      {8.025, "bleeding: the artery was cut before it was secured", "bleeding_events"},
      {14.1, "step not done: transect", "procedure.steps_done"}};
  EXPECT_EQ(overlay_text(d).errors, "errors 2 (N: next, P: previous)");
  d.timeline.current = 0;
  EXPECT_EQ(overlay_text(d).errors,
            "errors 2 (N: next, P: previous)  1/2 0:08.0 bleeding: the artery was cut before it "
            "was secured");
  d.branch = "BRANCH at 0:07.5 ...";
  d.replay_position_s = 15.6;
  d.timeline.current = -1;
  EXPECT_EQ(overlay_text(d).timeline, "0:15.6 in the branch (recording 0:14.1)  x1");
  EXPECT_EQ(overlay_text(d).errors.rfind("errors 2 (the recording's before the branch", 0), 0u);
}

// The instruments panel names what each hand holds and marks the active one, with its jaws, its
// pedal, the tissue between its jaws and its tip's distance to tissue; the controls panel lists
// every key the session reads.
TEST(OverlayText, TheInstrumentsPanelSaysWhatEachHandHolds) {
  OverlayData d;
  OverlayHand scissors;
  scissors.hand = "right";
  scissors.tool = "scissors";
  scissors.active = true;
  scissors.jaw_rad = 1.2;
  scissors.jaw_max_rad = 1.2;
  scissors.has_tissue = true;
  scissors.tissue_distance_m = 0.004;
  scissors.tissue_in_jaws_m = 0.007;
  OverlayHand grasper;
  grasper.hand = "left";
  grasper.tool = "grasper";
  grasper.jaw_max_rad = 1.0;
  OverlayHand hook;
  hook.hand = "left";
  hook.tool = "hook";
  hook.has_pedal = true;
  hook.pedal = true;
  hook.has_tissue = true;
  hook.tissue_distance_m = -0.001;
  OverlayHand holding = grasper;
  holding.hand = "right";
  holding.holding_nodes = 12;
  holding.has_tissue = true;
  holding.tissue_distance_m = -0.002;
  d.hands = {grasper, scissors, hook, holding};
  const OverlayText t = overlay_text(d);
  ASSERT_EQ(t.hands.size(), 4u);
  EXPECT_EQ(t.hands[0], "  left: grasper  jaws closed  tissue far");
  EXPECT_EQ(t.hands[1], "> right: scissors  jaws 1.20 of 1.20 rad  7 mm IN JAWS  tissue 4 mm");
  EXPECT_EQ(t.hands[2], "  left: hook  pedal DOWN  touching");
  EXPECT_EQ(t.hands[3], "  right: grasper  jaws closed  HOLDING  touching");
  std::string help;
  for (const std::string& l : overlay_help_lines()) help += l + "\n";
  for (const char* key : {"drag (left button)", "W / S", "wheel", "Q / E", "J ", "P ", "Home",
                          "Tab", "drag (right button)", "Space", "Esc", "F2"})
    EXPECT_NE(help.find(key), std::string::npos) << key;
}

}  // namespace
}  // namespace serosa::render
