// SnapshotOptions: how a frame is drawn (size, tessellation, which of the paper's views).
#pragma once

#include <array>

#include "render/lens_pass.h"

namespace serosa::render {

struct SnapshotOptions {
  /// The paper's Figure 11 views.
  enum class View {
    kVisual,      ///< Phong-tessellated, shaded surface with per-group materials and the wound
    kCollision,   ///< the surface triangles as they are (flat, faceted) with their wireframe
    kMechanical,  ///< the tet edges (RenderFrame::edges) as a see-through wireframe
  };

  int width = 640;   ///< pixels
  int height = 480;  ///< pixels
  /// Phong tessellation level: each triangle becomes level^2 triangles; 1 = flat (no
  /// tessellation). Clamped to [1, GL_MAX_TESS_GEN_LEVEL].
  int tessellation = 3;
  /// Phong tessellation shape factor alpha in [0, 1]: 0 = flat, 0.75 = the paper's choice.
  float shape_factor = 0.75f;
  View view = View::kVisual;
  /// Draw the depth cue under each tool's tip (render/tool_mesh.h append_depth_cue).
  bool depth_cue = true;
  /// Use auto_camera(frame) instead of frame.camera.
  bool fit_camera = false;
  /// The visual view's tissue detail (render/tissue_pattern.h: vessels, lobules, mottling, fine
  /// relief and the wound's rim); false: each material's plain colour, smoothly shaded (cheaper).
  bool detail = true;
  /// The visual view through the endoscope's optic (render/lens_pass.h): barrel distortion,
  /// vignette and edge anti-aliasing as a last pass; false: the pinhole picture as drawn.
  bool lens = true;
  LensSettings optic;
  /// Background colour (sRGB, [0, 1]): a dark abdominal cavity.
  std::array<float, 3> background{0.06f, 0.04f, 0.04f};
};

}  // namespace serosa::render
