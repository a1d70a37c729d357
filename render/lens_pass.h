// LensPass: the endoscope's optic over a drawn picture. The picture is drawn into the pass's own
// target, then copied onto the framebuffer bound before with a barrel distortion, the optic's
// vignette and an edge anti-aliasing (a luma-contrast blend along edges, cheaper on a software
// renderer than multisampling).
#pragma once

#include <memory>

#include "render/picture_target.h"

namespace serosa::render {

class GlProgram;

struct LensSettings {
  /// Barrel distortion: a point at relative radius r (1 at the picture's corner) is drawn where
  /// the pinhole picture has the point at r (1 + k r^2) / (1 + k), so the centre is magnified by
  /// 1 + k and the corners stay where they are. 0: none.
  float distortion = 0.06f;
  /// The fraction of light lost at the picture's corners (falling off smoothly from the centre),
  /// [0, 1). 0: none.
  float vignette = 0.35f;
  bool antialias = true;  ///< blend across high-contrast edges
};

class LensPass {
 public:
  /// Needs a current GL 4.1 core context (compiles its program).
  LensPass();
  ~LensPass();
  LensPass(const LensPass&) = delete;
  LensPass& operator=(const LensPass&) = delete;

  /// Before drawing: remembers the bound framebuffer and viewport, binds the pass's own target of
  /// width x height pixels (colour and depth) and sets the viewport to it.
  void begin(int width, int height);
  /// After drawing: binds the remembered framebuffer and viewport again and draws the picture
  /// through the optic over it (colour and alpha; depth untouched).
  void end(const LensSettings& lens);

 private:
  std::unique_ptr<GlProgram> program_;
  PictureTarget picture_;           // what is drawn through the optic
  int target_ = 0;                  // the framebuffer bound at begin()
  int viewport_[4] = {0, 0, 0, 0};  // and its viewport
};

}  // namespace serosa::render
