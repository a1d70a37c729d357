// PictureTarget: an offscreen colour texture with a depth buffer that a frame is drawn into and
// then drawn from, and the full-screen triangle that draws it (the pacer's lower resolutions,
// render/scaled_target.h, and the endoscope's optic, render/lens_pass.h). Needs a current GL 4.1
// core context.
#pragma once

namespace serosa::render {

/// A vertex shader for glDrawArrays(GL_TRIANGLES, 0, 3) with no attributes: one triangle
/// covering the viewport, its `v_uv` running over [0, 1] across it.
extern const char* const kFullScreenVertex;

class PictureTarget {
 public:
  PictureTarget() = default;
  ~PictureTarget();
  PictureTarget(const PictureTarget&) = delete;
  PictureTarget& operator=(const PictureTarget&) = delete;

  /// Sizes the target to width x height pixels (made on first use, remade on a new size), binds
  /// it and sets the viewport to it.
  void bind(int width, int height);
  /// Draws the full-screen triangle with the target's colour bound on texture unit 0 (the
  /// caller's program is in use and reads it).
  void draw_full_screen() const;

  [[nodiscard]] int width() const { return width_; }
  [[nodiscard]] int height() const { return height_; }

 private:
  unsigned int fbo_ = 0, color_ = 0, depth_ = 0, vao_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace serosa::render
