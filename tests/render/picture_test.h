// The fixture of the tests that render pictures offscreen: a 320 x 240 GL context per test, and
// shoot() to render a frame and write it for a person to look at.
#pragma once

#include <gtest/gtest.h>

#include <exception>
#include <memory>
#include <string>

#include "render/gl_context.h"
#include "render/png_writer.h"
#include "render/render_fixtures.h"
#include "render/snapshot.h"

namespace serosa::render::fixtures {

class PictureTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      ctx_ = std::make_unique<OffscreenContext>(320, 240);
      pin_gl_driver();  // no false leak reports at exit (see render_fixtures.h)
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
  }
  void TearDown() override { ctx_.reset(); }

  // Renders and writes `name`.png.
  Image shoot(const RenderFrame& f, const SnapshotOptions& o, const std::string& name) {
    Image img = render_image(*ctx_, f, o);
    write_png(img, output_path(name + ".png"));
    return img;
  }

  std::unique_ptr<OffscreenContext> ctx_;
};

}  // namespace serosa::render::fixtures
