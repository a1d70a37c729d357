// Pictures of a running simulation, drawn offscreen (EGL) for `serosa headless --frames` and
// `serosa replay --frames`: the organs' boundary surface with its wound (cut faces flagged against
// the uncut surface, surface/cut_faces.h) and the instruments at their current poses, seen by a
// the scene's endoscope (or, on request or with no posed endoscope, a camera fitted once to the
// organs).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/drawn_surface.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "render/image.h"
#include "render/render_frame.h"
#include "render/snapshot_options.h"

namespace serosa::render {
class OffscreenContext;
}

namespace serosa::app {

class FramePictures {
 public:
  using View = render::SnapshotOptions::View;

  /// Opens an offscreen context of the scene's render size (at most 960 x 540) and takes the
  /// uncut surface of `initial` as the wound reference: construct it BEFORE the first cut.
  /// `views`: which of the paper's views each take() writes (the first is written as STEM.png,
  /// the others as STEM_<view>.png). @throws std::runtime_error when no GL context can be had
  FramePictures(std::filesystem::path dir, const Scene& scene, const TetMesh& initial,
                std::map<int, std::string> group_names, std::vector<View> views = {View::kVisual});
  ~FramePictures();
  FramePictures(const FramePictures&) = delete;
  FramePictures& operator=(const FramePictures&) = delete;

  /// The frame of `state` (surface with wound flags, tet edges, tools, camera), as drawn.
  [[nodiscard]] const render::RenderFrame& frame(const SimState& state);
  /// The picture of `state` in `view`.
  [[nodiscard]] render::Image image(const SimState& state, View view);
  /// Writes the pictures of `state` (one per view) into the folder; returns their paths.
  std::vector<std::filesystem::path> take(const SimState& state, const std::string& stem);

  [[nodiscard]] const render::SnapshotOptions& options() const { return m_options; }
  /// Look through the scene's endoscope while a device poses it (the default), or (false) always
  /// through a camera fitted once to the organs, the same for every picture.
  void set_endoscope(bool on) { m_endoscope = on; }
  /// The share of 16 x 16 tiles with no detail in the last take()'s first picture
  /// (render/image_stats.h flat_block_fraction), [0, 1].
  [[nodiscard]] double flat_fraction() const { return m_flat; }
  /// The share of its pixels that read as blood (render/image_stats.h blood_fraction), [0, 1].
  [[nodiscard]] double blood_fraction() const { return m_blood; }
  /// The camera of the last picture: "endoscope" or "fitted".
  [[nodiscard]] const char* camera_used() const { return m_used_scope ? "endoscope" : "fitted"; }
  /// Look through `camera` from now on instead of the fitted one or the endoscope (a close-up).
  void set_camera(const render::Camera& camera) {
    m_fitted = camera;
    m_endoscope = false;
  }

 private:
  std::filesystem::path m_dir;
  const Scene& m_scene;
  std::map<int, std::string> m_names;
  std::vector<View> m_views;
  DrawnSurface m_drawn;  // the surface stage's surface, or its own
  render::SnapshotOptions m_options;
  std::unique_ptr<render::OffscreenContext> m_context;
  render::RenderFrame m_frame;
  std::optional<render::Camera> m_fitted;
  bool m_endoscope = true;
  bool m_used_scope = false;
  double m_flat = 0.0;
  double m_blood = 0.0;
};

}  // namespace serosa::app
