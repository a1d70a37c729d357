// `serosa bench render`: what each feature of the endoscopic picture costs per frame. The default
// appendectomy is run on its scripted procedure to the clip (2.5 s; 1.0 s with --quick), and its
// frame, seen through the endoscope with the abdomen around it, is drawn offscreen (EGL; Mesa's
// llvmpipe on a machine without a GPU) with the features added one by one: the plain colours
// (smooth shading only, drawn into the 4x multisampled target as the window's), the optic (barrel
// distortion and vignette: the picture is drawn single-sampled into the optic's own target), its
// edge anti-aliasing, the tissue's pattern and relief; at tessellation 1 and 3, at the window's
// 1280 x 720 and the pacer's half resolution. The picture's detail is the share of flat 16 x 16
// tiles (render/image_stats.h): the accuracy axis, lower is better.
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "app/assemble_state.h"
#include "app/render_frame_from_surface.h"
#include "app/scenery_from_scene.h"
#include "app/simulation.h"
#include "bench/suite/bench_parts.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/image_stats.h"
#include "render/png_writer.h"
#include "render/render_frame.h"
#include "render/snapshot_options.h"

namespace serosa::bench {

using namespace serosa::app;  // the driver and the composition the scenes run on
namespace {

using Clock = std::chrono::steady_clock;

struct Features {
  std::string label;
  bool detail = false;
  bool lens = false;
  bool antialias = false;
};

// The default scene's frame after `seconds` of its scripted procedure, through its endoscope,
// stepped by the headless driver.
render::RenderFrame scene_frame(const BenchOptions& options, double seconds) {
  HeadlessOptions o;
  o.scene = options.assets_dir / ".." / "config" / "appendectomy.toml";
  o.progress = false;
  o.scene_record = false;
  o.seconds = seconds;
  Simulation sim(o);
  const Scene& scene = sim.scene();
  const AssembledScene& assembled = sim.assembled();
  const TetMesh initial = sim.state().mesh;
  for (std::int64_t k = 0; k < sim.planned_steps(); ++k) sim.step();
  const SimState& state = sim.state();
  render::RenderFrame f;
  fill_render_frame(state.mesh, state.shared.surface,
                    drawn_group_names(scene, assembled.group_names()), false, f,
                    &state.blocks.cutting.coagulated, state.blocks.cutting.coagulated_version,
                    &state.blocks.bleeding.stain);
  fill_render_tools(scene, state, f);
  f.scenery = scenery_from_scene(scene, initial);
  fill_taenia(initial, drawn_group_names(scene, assembled.group_names()), f);
  if (const auto scope = endoscope_view(scene, state)) f.camera = *scope;
  return f;
}

struct Drawn {
  double ms = 0.0;    // mean wall time of a frame, glFinish included, ms
  double flat = 0.0;  // share of flat tiles of its picture
};

Drawn draw(render::OffscreenContext& ctx, render::FrameRenderer& renderer,
           const render::RenderFrame& f, const render::SnapshotOptions& o, int frames,
           const std::filesystem::path& png) {
  ctx.resize(o.width, o.height);
  ctx.bind_framebuffer();
  renderer.draw(f, o, o.width, o.height);  // warm-up: uploads
  ctx.finish();
  const auto t0 = Clock::now();
  for (int i = 0; i < frames; ++i) {
    ctx.bind_framebuffer();
    renderer.draw(f, o, o.width, o.height);
    ctx.finish();
  }
  Drawn d;
  d.ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / frames;
  const render::Image image = ctx.read_image();
  d.flat = render::flat_block_fraction(image);
  if (!png.empty()) render::write_png(image, png);
  return d;
}

}  // namespace

PartResult run_render_part(const BenchOptions& options) {
  const int frames = options.quick ? 2 : 10;
  const render::RenderFrame frame = scene_frame(options, options.quick ? 1.0 : 2.5);
  const std::vector<Features> features{{"plain", false, false, false},
                                       {"+ optic", false, true, false},
                                       {"+ anti-aliasing", false, true, true},
                                       {"+ pattern", true, true, true}};
  PartResult result;
  render::OffscreenContext ctx(1280, 720);
  ctx.make_current();
  {
    render::FrameRenderer renderer;
    for (const int level : {1, 3}) {
      for (const float scale : {1.0f, 0.5f}) {
        const std::string res = scale == 1.0f ? "1280x720" : "640x360";
        Table t{"render_" + res + "_tess" + std::to_string(level),
                {"features", "ms_per_frame", "flat_fraction"},
                {},
                {}};
        for (std::size_t i = 0; i < features.size(); ++i) {
          const Features& feat = features[i];
          render::SnapshotOptions o;
          o.width = static_cast<int>(std::lround(1280 * scale));
          o.height = static_cast<int>(std::lround(720 * scale));
          o.tessellation = level;
          o.detail = feat.detail;
          o.lens = feat.lens;
          o.optic.antialias = feat.antialias;
          const bool keep = level == 3 && scale == 1.0f && (i == 0 || i + 1 == features.size());
          const auto png =
              keep ? options.out / ("render_" + std::string(i == 0 ? "plain" : "full") + ".png")
                   : std::filesystem::path{};
          const Drawn d = draw(ctx, renderer, frame, o, frames, png);
          t.add(feat.label, {static_cast<double>(i), d.ms, d.flat});
        }
        result.notes.push_back(t.name + ": plain " + fmt_double("%.1f ms", t.rows.front()[1]) +
                               " (" + fmt_double("%.0f %% flat", 100 * t.rows.front()[2]) +
                               "), everything " + fmt_double("%.1f ms", t.rows.back()[1]) + " (" +
                               fmt_double("%.0f %% flat", 100 * t.rows.back()[2]) + ")");
        result.tables.push_back(std::move(t));
      }
    }
  }  // the renderer's GL objects go before the context
  Plot p{"render_features",
         "Endoscopic picture: detail against frame time",
         "ms per frame",
         "share of flat 16x16 tiles",
         false,
         false,
         {}};
  for (const Table& t : result.tables)
    p.series.push_back({t.name, "ms_per_frame", "flat_fraction", t.name.substr(7), false, true});
  result.plots.push_back(std::move(p));
  result.checks.push_back({"render_1280x720_tess3", "features", "flat_fraction",
                           Direction::decreasing, 0.05, 0.01,
                           "each feature keeps or adds detail: flat tiles never grow by much"});
  return result;
}

}  // namespace serosa::bench
