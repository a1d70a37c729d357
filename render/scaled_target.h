// ScaledTarget: draws a frame at a fraction of the framebuffer's resolution and stretches it over
// the framebuffer. A software renderer's cost (Mesa's llvmpipe) follows the pixels it shades, so
// this is the window's cheapest way to give CPU back to the solver (window/frame_pacer.h's last
// resort before dropping frames). At scale 1 it is a pass-through: the frame is drawn directly.
#pragma once

#include <memory>

#include "render/picture_target.h"

namespace serosa::render {

class GlProgram;

/// The size a frame is drawn at for `scale` of width x height: round(scale x width) x
/// round(scale x height), at least 1 each, scale clamped to [0.1, 1] (1 when not finite).
void scaled_size(int width, int height, float scale, int& draw_width, int& draw_height);

class ScaledTarget {
 public:
  /// Needs a current GL 4.1 core context (compiles its program).
  ScaledTarget();
  ~ScaledTarget();
  ScaledTarget(const ScaledTarget&) = delete;
  ScaledTarget& operator=(const ScaledTarget&) = delete;

  /// Before drawing: remembers the framebuffer bound now (the window's, or an offscreen one) and,
  /// below scale 1, binds an offscreen target of round(scale x width) x round(scale x height)
  /// pixels (at least 1) and sets the viewport to it. scale is clamped to [0.1, 1]. The size to
  /// draw at is written to draw_width, draw_height.
  void begin(int width, int height, float scale, int& draw_width, int& draw_height);
  /// After drawing: below scale 1, binds the remembered framebuffer again, sets the viewport to
  /// width x height and stretches the drawn picture over it (bilinear); nothing at scale 1.
  void present(int width, int height);

  [[nodiscard]] float scale() const { return scale_; }

 private:
  std::unique_ptr<GlProgram> program_;
  PictureTarget target_picture_;  // the lower resolution's picture
  int target_ = 0;                // the framebuffer bound at begin()
  float scale_ = 1.0f;
};

}  // namespace serosa::render
