// `serosa bench tessellation`: Phong tessellation level (each triangle drawn as level² triangles,
// shape factor 0.75) against frame time.
//  - sphere: an icosphere of 80 triangles with exact (radial) normals, tessellated on the CPU with
//    the shader's formula (render/phong_tessellation.h), against the true sphere; and, at level 2,
//    icospheres of growing resolution (Phong and flat), whose distance must fall.
//  - organs: the rest boundary of <organ>_coarse.msh (area-weighted vertex normals), tessellated,
//    against the boundary of <organ>_fine.msh (render/surface_distance.h, as bench/render's
//    BM_OrganAccuracy): vertex and centroid distances. Not monotone (the Rendering section of
//    docs/BENCHMARKS.md: tessellation moves these organs away from the fine surface), so no check.
//  - frame time: one 640 x 480 frame with 4x MSAA of that surface through the visual view's
//    tessellation shaders, offscreen GL through EGL (Mesa llvmpipe on a machine without a GPU).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bench/suite/bench_parts.h"
#include "engine/io/mesh_io.h"
#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/icosphere.h"
#include "render/phong_tessellation.h"
#include "render/render_frame.h"
#include "render/snapshot_options.h"
#include "render/surface_distance.h"
#include "render/vertex_normals.h"

namespace serosa::bench {
namespace {

using render::TriMesh;
using Clock = std::chrono::steady_clock;

constexpr int kWidth = 640;
constexpr int kHeight = 480;
constexpr float kAlpha = 0.75f;

/// Mean time of `frames` frames (after one warm-up) of `surface` at `level`, ms.
double frame_ms(render::OffscreenContext& ctx, render::FrameRenderer& renderer,
                const TriMesh& surface, const std::vector<float>& normals, const std::string& name,
                int level, int frames) {
  render::RenderFrame f;
  f.pos = surface.pos;
  f.nrm = normals;
  f.tri = surface.tri;
  f.tri_group.assign(f.num_triangles(), 1);
  f.tri_cut.assign(f.num_triangles(), 0);
  f.group_names = {"", name};
  render::SnapshotOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.tessellation = level;
  o.fit_camera = true;
  ctx.bind_framebuffer();
  renderer.draw(f, o, kWidth, kHeight);
  ctx.finish();
  const auto t0 = Clock::now();
  for (int i = 0; i < frames; ++i) {
    ctx.bind_framebuffer();
    renderer.draw(f, o, kWidth, kHeight);
    ctx.finish();
  }
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count() / frames;
}

std::string level_label(int level) { return "level " + std::to_string(level); }

}  // namespace

PartResult run_tessellation_part(const BenchOptions& options) {
  const int max_level = options.quick ? 3 : 6;
  const int frames = options.quick ? 2 : 20;
  render::OffscreenContext ctx(kWidth, kHeight, 4);
  ctx.make_current();
  PartResult result;
  {
    render::FrameRenderer renderer;

    // Sphere against the true sphere, against the level.
    const TriMesh sphere = render::icosphere(1, 1.0f);
    const std::vector<float> radial = sphere.pos;              // the true sphere's normals
    const TriMesh drawn_sphere = render::icosphere(1, 0.02f);  // 2 cm: an organ's size
    const std::vector<float> drawn_normals =
        render::compute_vertex_normals(drawn_sphere.pos, drawn_sphere.tri);
    Table ts{"tessellation_sphere",
             {"level", "drawn_triangles", "max_dist_rel", "mean_dist_rel", "ms_per_frame"},
             {},
             {}};
    for (int level = 1; level <= max_level; ++level) {
      const TriMesh m = render::phong_tessellate(sphere.pos, radial, sphere.tri, level, kAlpha);
      const render::SphereDistance d = render::distance_to_sphere(m, 1.0);
      const double ms =
          frame_ms(ctx, renderer, drawn_sphere, drawn_normals, "appendix", level, frames);
      ts.add(level_label(level), {static_cast<double>(level), static_cast<double>(m.tri.size() / 3),
                                  d.max_m, d.mean_m, ms});
    }
    // At level 2, icospheres of growing resolution: Phong and flat.
    Table tr{"tessellation_sphere_inputs",
             {"input_triangles", "phong_level2_max_dist_rel", "flat_max_dist_rel"},
             {},
             {}};
    for (int subdiv = 0; subdiv <= (options.quick ? 2 : 3); ++subdiv) {
      const TriMesh s = render::icosphere(subdiv, 1.0f);
      const render::SphereDistance phong =
          render::distance_to_sphere(render::phong_tessellate(s.pos, s.pos, s.tri, 2, kAlpha), 1.0);
      const render::SphereDistance flat = render::distance_to_sphere(s, 1.0);
      tr.add("icosphere " + std::to_string(subdiv),
             {static_cast<double>(s.tri.size() / 3), phong.max_m, flat.max_m});
    }
    result.checks.push_back({ts.name, "level", "mean_dist_rel", Direction::decreasing, 0.0, 0.0,
                             "level 1 to 2 only: see the note"});
    result.tables.push_back(std::move(ts));
    result.tables.push_back(std::move(tr));

    // Organs: coarse Phong-tessellated boundary against the fine boundary.
    for (const std::string organ : {"liver", "appendectomy"}) {
      const auto dir = options.assets_dir;
      const TriMesh coarse = render::rest_boundary(read_mesh(dir / (organ + "_coarse.msh")));
      const TriMesh fine = render::rest_boundary(read_mesh(dir / (organ + "_fine.msh")));
      const std::vector<float> nrm = render::compute_vertex_normals(coarse.pos, coarse.tri);
      const render::SurfaceDistance reference(fine);
      Table t{"tessellation_" + organ,
              {"level", "drawn_triangles", "max_dist_mm", "mean_dist_mm", "ms_per_frame"},
              {},
              {}};
      for (int level = 1; level <= max_level; ++level) {
        const TriMesh m = render::phong_tessellate(coarse.pos, nrm, coarse.tri, level, kAlpha);
        const render::MeshDistance d = render::mesh_distance(m, reference);
        const double ms = frame_ms(ctx, renderer, coarse, nrm,
                                   organ == "liver" ? "liver" : "appendix", level, frames);
        t.add(level_label(level),
              {static_cast<double>(level), static_cast<double>(m.tri.size() / 3), 1e3 * d.max_m,
               1e3 * d.mean_m, ms});
      }
      result.tables.push_back(std::move(t));
    }
  }  // the renderer's GL objects go before the context
  // The sphere's check: only the step from flat to level 2 must lower the mean distance.
  {
    Table& ts = result.tables.front();
    Table first{"tessellation_sphere_flat_vs_phong", ts.columns, {}, {}};
    first.add(ts.settings[0], ts.rows[0]);
    first.add(ts.settings[1], ts.rows[1]);
    result.checks.front().table = first.name;
    result.checks.front().why =
        "on the sphere, Phong level 2 is closer to the true sphere than flat (level 1); higher "
        "levels are not closer (shape factor 0.75 overshoots)";
    result.tables.push_back(std::move(first));
  }
  result.checks.push_back({"tessellation_sphere_inputs", "input_triangles",
                           "phong_level2_max_dist_rel", Direction::decreasing, 0.0, 0.0,
                           "a finer input sphere is closer at a fixed level"});
  result.checks.push_back({"tessellation_sphere_inputs", "input_triangles", "flat_max_dist_rel",
                           Direction::decreasing, 0.0, 0.0,
                           "a finer flat sphere is closer (the reference curve)"});

  Plot sphere{"tessellation_sphere",
              "Tessellation: sphere (80 triangles) against frame time",
              "frame time (640 x 480, 4x MSAA), ms",
              "distance to the true sphere / radius",
              false,
              true,
              {}};
  sphere.series.push_back(
      {"tessellation_sphere", "ms_per_frame", "max_dist_rel", "max", false, true});
  sphere.series.push_back(
      {"tessellation_sphere", "ms_per_frame", "mean_dist_rel", "mean", false, true});
  result.plots.push_back(std::move(sphere));
  Plot organs{"tessellation_organs",
              "Tessellation: coarse organ boundary against the fine one, by level",
              "frame time (640 x 480, 4x MSAA), ms",
              "mean distance to the fine boundary, mm",
              false,
              false,
              {}};
  organs.series.push_back(
      {"tessellation_liver", "ms_per_frame", "mean_dist_mm", "liver", false, true});
  organs.series.push_back(
      {"tessellation_appendectomy", "ms_per_frame", "mean_dist_mm", "appendectomy", false, true});
  result.plots.push_back(std::move(organs));
  std::string note = "tessellation: GL renderer ";
  note.append(ctx.gl_renderer())
      .append(
          "; on the sphere only flat -> level 2 gets closer, higher levels overshoot; the "
          "organs' coarse meshes move away from the fine surface with the level");
  result.notes.push_back(std::move(note));
  return result;
}

}  // namespace serosa::bench
