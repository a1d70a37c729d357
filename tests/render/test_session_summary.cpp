// The end-of-session summary: its text says the verdict, the score, the five domains and why it
// failed; drawn through EGL it puts a banner of the verdict's colour in the middle of the
// picture (green when passed, red when not), and nothing of the other colour.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <string>

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/overlay.h"
#include "render/png_writer.h"
#include "render/render_fixtures.h"
#include "render/session_summary.h"

namespace serosa::render {
namespace {

SessionSummary sample(bool passed) {
  SessionSummary s;
  s.title = "Appendix transection";
  s.score = passed ? 95.6 : 76.6;
  s.pass_score = 80.0;
  s.passed = passed;
  s.domains = {{"depth perception", passed ? 4 : 2},
               {"bimanual dexterity", 5},
               {"efficiency", 4},
               {"tissue handling", 4},
               {"autonomy", 5}};
  if (!passed) {
    s.failed = {"score 77 under the pass score of 80",
                "cut.collateral_m3 = 5.1e-08 m^3, above the limit of 2e-08 (critical)"};
    s.below = {"time_s = 12 s, above the limit of 10", s.failed[1]};
  }
  return s;
}

TEST(SessionSummary, TheTextSaysTheVerdictTheScoreTheDomainsAndWhy) {
  const std::vector<std::string> ok = summary_text(sample(true));
  EXPECT_EQ(ok[0], "Appendix transection");
  EXPECT_EQ(ok[1], "PASSED");
  EXPECT_EQ(ok[2], "score 96 of 100 (80 to pass)");
  EXPECT_EQ(ok[3], "depth perception  4 / 5");
  EXPECT_EQ(ok[7], "autonomy  5 / 5");
  EXPECT_EQ(ok.size(), 9u);  // no "Why:" nor "To work on:" when it passed with nothing below

  const std::vector<std::string> no = summary_text(sample(false));
  EXPECT_EQ(no[1], "NOT PASSED");
  EXPECT_EQ(no[8], "Why:");
  EXPECT_EQ(no[9], "  score 77 under the pass score of 80");
  EXPECT_EQ(no[11], "To work on:");  // only what "Why:" did not say already
  EXPECT_EQ(no[12], "  time_s = 12 s, above the limit of 10");
  EXPECT_EQ(no.size(), 14u);
  EXPECT_EQ(no.back(), "Esc, Space or close the window to leave");
}

// Pixels within 12 of `rgb` in every channel, in the central half of the picture.
std::size_t pixels_of(const Image& img, const unsigned char rgb[3]) {
  std::size_t n = 0;
  for (int y = img.height / 4; y < 3 * img.height / 4; ++y)
    for (int x = img.width / 4; x < 3 * img.width / 4; ++x) {
      const auto p = img.at(x, y);
      bool near = true;
      for (int k = 0; k < 3; ++k) near = near && std::abs(p[k] - static_cast<int>(rgb[k])) <= 12;
      n += near ? 1 : 0;
    }
  return n;
}

TEST(SessionSummary, DrawnItShowsABannerOfTheVerdictsColour) {
  constexpr int kW = 640, kH = 480;
  std::unique_ptr<OffscreenContext> ctx;
  std::unique_ptr<FrameRenderer> renderer;
  std::unique_ptr<Overlay> overlay;
  try {
    ctx = std::make_unique<OffscreenContext>(kW, kH);
    fixtures::pin_gl_driver();
    renderer = std::make_unique<FrameRenderer>();
    overlay = std::make_unique<Overlay>();
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  RenderFrame frame = fixtures::frame_of(fixtures::icosphere(2, 0.02f));
  SnapshotOptions options;
  options.width = kW;
  options.height = kH;
  options.fit_camera = true;
  for (const bool passed : {true, false}) {
    ctx->bind_framebuffer();
    renderer->draw(frame, options, kW, kH);
    const Image before = ctx->read_image();  // (leaves the default framebuffer bound)
    ctx->bind_framebuffer();
    renderer->draw(frame, options, kW, kH);
    overlay->draw_summary(sample(passed), kW, kH);
    const Image img = ctx->read_image();
    write_png(img, fixtures::output_path(passed ? "summary_passed.png" : "summary_failed.png"));
    const unsigned char* mine = passed ? kPassedRgb : kFailedRgb;
    const unsigned char* other = passed ? kFailedRgb : kPassedRgb;
    EXPECT_EQ(pixels_of(before, mine), 0u);
    EXPECT_GT(pixels_of(img, mine), 5000u) << (passed ? "passed" : "failed");  // a 400 x 40 bar
    EXPECT_EQ(pixels_of(img, other), 0u);
  }
}

}  // namespace
}  // namespace serosa::render
