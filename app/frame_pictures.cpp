#include "app/frame_pictures.h"

#include <algorithm>

#include "app/render_frame_from_surface.h"
#include "app/scenery_from_scene.h"
#include "render/camera.h"
#include "render/gl_context.h"
#include "render/image_stats.h"
#include "render/overlay.h"
#include "render/png_writer.h"
#include "render/snapshot.h"

namespace serosa::app {

FramePictures::FramePictures(std::filesystem::path dir, const Scene& scene, const TetMesh& initial,
                             std::map<int, std::string> group_names, std::vector<View> views)
    : m_dir(std::move(dir)),
      m_scene(scene),
      m_names(drawn_group_names(scene, std::move(group_names))),
      m_views(std::move(views)),
      m_drawn(initial) {
  if (m_views.empty()) m_views.push_back(View::kVisual);
  std::filesystem::create_directories(m_dir);
  m_options.width = std::min(scene.render.width, 960);
  m_options.height = std::min(scene.render.height, 540);
  m_options.tessellation = scene.render.tessellation;
  m_options.shape_factor = static_cast<float>(scene.render.shape_factor);
  m_context = std::make_unique<render::OffscreenContext>(m_options.width, m_options.height);
  m_frame.scenery = scenery_from_scene(scene, initial);  // once: frame() leaves it as it is
  fill_taenia(initial, m_names, m_frame);                // likewise
}

FramePictures::~FramePictures() = default;

const render::RenderFrame& FramePictures::frame(const SimState& state) {
  fill_render_frame(state.mesh, m_drawn.of(state), m_names, /*with_edges=*/true, m_frame,
                    &state.blocks.cutting.coagulated, state.blocks.cutting.coagulated_version,
                    &state.blocks.bleeding.stain);
  fill_render_tools(m_scene, state, m_frame);
  const auto scope = m_endoscope ? endoscope_view(m_scene, state) : std::nullopt;
  m_used_scope = scope.has_value();
  if (scope) {
    m_frame.camera = *scope;
  } else {
    // Fitted once, on the first picture, so that motion shows between pictures.
    // (auto_camera fits the organs only, not the tools' shafts reaching out to their trocars.)
    if (!m_fitted)
      m_fitted = render::auto_camera(
          m_frame, static_cast<float>(m_options.width) / static_cast<float>(m_options.height));
    m_frame.camera = *m_fitted;
  }
  return m_frame;
}

render::Image FramePictures::image(const SimState& state, View view) {
  (void)frame(state);
  render::SnapshotOptions o = m_options;
  o.view = view;
  return render::render_image(*m_context, m_frame, o);
}

std::vector<std::filesystem::path> FramePictures::take(const SimState& state,
                                                       const std::string& stem) {
  (void)frame(state);
  std::vector<std::filesystem::path> out;
  for (std::size_t i = 0; i < m_views.size(); ++i) {
    render::SnapshotOptions o = m_options;
    o.view = m_views[i];
    std::string name = stem;
    if (i > 0) name.append("_").append(render::view_name(m_views[i]));
    name.append(".png");
    out.push_back(m_dir / name);
    const render::Image image = render::render_image(*m_context, m_frame, o);
    if (i == 0) {
      m_flat = render::flat_block_fraction(image);
      m_blood = render::blood_fraction(image);
    }
    render::write_png(image, out.back());
  }
  return out;
}

}  // namespace serosa::app
