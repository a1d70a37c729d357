// Rendering benchmarks (docs/BENCHMARKS.md "Rendering"):
//  - BM_FrameTime: one frame of the visual view (Phong tessellation, 640 x 480, 4x MSAA) through
//    EGL, against the tessellation level (1..6) and the surface size (icospheres of 20 * 4^k
//    triangles). The GL renderer is whatever EGL gives: Mesa llvmpipe (CPU) on the dev VM; the
//    benchmark's label names it.
//  - BM_PatchesPerDraw: the same frame (5,120 triangles, level 3) with the tessellated surface
//    split into draws of at most N patches (0: one draw), FrameRenderer::set_patches_per_draw.
//  - BM_PhongAccuracy: how far the tessellated surface is from the true sphere that a coarse
//    icosphere with exact (radial) normals approximates, against the level; computed on the CPU
//    with the shader's formula (render/phong_tessellation.h). BM_RefinedAccuracy gives the same
//    for flat, finer icospheres of equal triangle counts, for comparison.
//  - BM_OrganAccuracy: the same question on the bundled organs: the boundary of the coarse mesh
//    (assets/<organ>_coarse.msh, area-weighted vertex normals), Phong-tessellated, against the
//    boundary of the fine mesh of the same organ (<organ>_fine.msh) as the finer reference:
//    distance from every tessellated vertex and triangle centroid to the nearest fine triangle
//    (render/surface_distance.h, as `serosa bench tessellation`).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>

#include "engine/io/mesh_io.h"

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/phong_tessellation.h"
#include "render/surface_distance.h"
#include "render/vertex_normals.h"
#include "tests/render/render_fixtures.h"

namespace serosa::render {
namespace {

constexpr int kWidth = 640;
constexpr int kHeight = 480;

// One EGL context per process (see gl_context.h), made on first use.
OffscreenContext& context() {
  static const std::unique_ptr<OffscreenContext> ctx =
      std::make_unique<OffscreenContext>(kWidth, kHeight, 4);
  return *ctx;
}

// Draws `f` once (uploads indices, compiles the pipeline), then once per iteration, each frame
// finished before the next.
void time_frames(benchmark::State& state, OffscreenContext& ctx, FrameRenderer& r,
                 const RenderFrame& f, const SnapshotOptions& o) {
  ctx.bind_framebuffer();
  r.draw(f, o, kWidth, kHeight);
  ctx.finish();
  for (auto _ : state) {
    ctx.bind_framebuffer();
    r.draw(f, o, kWidth, kHeight);
    ctx.finish();
  }
}

void BM_FrameTime(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  const int subdiv = static_cast<int>(state.range(1));
  OffscreenContext& ctx = context();
  ctx.make_current();
  ctx.resize(kWidth, kHeight);
  RenderFrame f = fixtures::frame_of(fixtures::icosphere(subdiv, 0.02f));
  f.group_names = {"", "appendix"};
  SnapshotOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.tessellation = level;
  o.fit_camera = true;
  FrameRenderer r;
  time_frames(state, ctx, r, f, o);
  const double t = static_cast<double>(f.num_triangles());
  state.counters["triangles"] = t;
  state.counters["drawn_triangles"] = t * level * level;
  state.SetLabel(ctx.gl_renderer());
}
BENCHMARK(BM_FrameTime)
    ->ArgsProduct({{1, 2, 3, 4, 5, 6}, {0, 1, 2, 3, 4}})
    ->ArgNames({"level", "subdiv"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// One frame of the 5,120-triangle sphere at level 3, the tessellated surface in draws of at most
// range(0) patches (0: one draw for all).
void BM_PatchesPerDraw(benchmark::State& state) {
  OffscreenContext& ctx = context();
  ctx.make_current();
  ctx.resize(kWidth, kHeight);
  RenderFrame f = fixtures::frame_of(fixtures::icosphere(4, 0.02f));
  f.group_names = {"", "appendix"};
  SnapshotOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.tessellation = 3;
  o.fit_camera = true;
  FrameRenderer r;
  r.set_patches_per_draw(static_cast<std::size_t>(state.range(0)));
  time_frames(state, ctx, r, f, o);
  state.counters["draws"] = state.range(0) == 0 ? 1.0 : std::ceil(5120.0 / state.range(0));
  state.SetLabel(ctx.gl_renderer());
}
BENCHMARK(BM_PatchesPerDraw)
    ->Arg(0)
    ->Arg(16)
    ->Arg(64)
    ->Arg(256)
    ->Arg(1024)
    ->ArgName("patches")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Sphere of radius 1 from icosphere(subdiv) with radial normals, tessellated at `level`.
// The trainee's depth cue (render/tool_mesh.h append_depth_cue) and the active instrument's
// collar: one frame of the 1,280-triangle sphere at level 3 with a grasper and scissors held
// near it, without (0) and with (1) a ring on the surface under each tip.
void BM_DepthCue(benchmark::State& state) {
  OffscreenContext& ctx = context();
  ctx.make_current();
  ctx.resize(kWidth, kHeight);
  RenderFrame f = fixtures::frame_of(fixtures::icosphere(3, 0.02f));
  f.group_names = {"", "appendix"};
  for (int k = 0; k < 2; ++k) {
    RenderTool t;
    t.kind = k == 0 ? RenderTool::Kind::kGrasper : RenderTool::Kind::kScissors;
    const float side = k == 0 ? -0.008f : 0.008f;
    t.tip = {side, 0.0f, 0.026f};
    t.jaw_rad = 0.8f;
    t.active = k == 1;
    t.has_tissue = true;
    t.tissue_point = {side, 0.0f, 0.0199f};
    t.tissue_normal = {0.0f, 0.0f, 1.0f};
    t.tissue_distance_m = 0.006f;
    f.tools.push_back(t);
  }
  SnapshotOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.tessellation = 3;
  o.fit_camera = true;
  o.depth_cue = state.range(0) != 0;
  FrameRenderer r;
  time_frames(state, ctx, r, f, o);
  state.SetLabel(ctx.gl_renderer());
}
BENCHMARK(BM_DepthCue)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("cue")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_PhongAccuracy(benchmark::State& state) {
  const int level = static_cast<int>(state.range(0));
  const int subdiv = static_cast<int>(state.range(1));
  const auto s = fixtures::icosphere(subdiv, 1.0f);
  const std::vector<float> nrm = s.pos;  // radial: the true sphere's normals
  TriMesh m;
  for (auto _ : state) {
    m = phong_tessellate(s.pos, nrm, s.tri, level, 0.75f);
    benchmark::DoNotOptimize(m.pos.data());
  }
  const SphereDistance d = distance_to_sphere(m, 1.0);
  const SphereDistance flat = distance_to_sphere(phong_tessellate(s.pos, nrm, s.tri, 1, 0.0f), 1.0);
  state.counters["triangles"] = static_cast<double>(m.tri.size() / 3);
  state.counters["max_dist_rel"] = d.max_m;  // relative to the radius
  state.counters["mean_dist_rel"] = d.mean_m;
  state.counters["flat_max_dist_rel"] = flat.max_m;
}
BENCHMARK(BM_PhongAccuracy)
    ->ArgsProduct({{1, 2, 3, 4, 5, 6}, {0, 1, 2}})
    ->ArgNames({"level", "subdiv"})
    ->Unit(benchmark::kMicrosecond);

// Flat icospheres: the reference a finer mesh gives for the same triangle count.
void BM_RefinedAccuracy(benchmark::State& state) {
  const int subdiv = static_cast<int>(state.range(0));
  fixtures::Surface s;
  for (auto _ : state) {
    s = fixtures::icosphere(subdiv, 1.0f);
    benchmark::DoNotOptimize(s.pos.data());
  }
  TriMesh m{s.pos, s.tri};
  const SphereDistance d = distance_to_sphere(m, 1.0);
  state.counters["triangles"] = static_cast<double>(s.tri.size() / 3);
  state.counters["max_dist_rel"] = d.max_m;
  state.counters["mean_dist_rel"] = d.mean_m;
}
BENCHMARK(BM_RefinedAccuracy)->DenseRange(0, 4)->ArgName("subdiv")->Unit(benchmark::kMicrosecond);

// ---- organs: coarse Phong-tessellated boundary against the fine boundary -------------------

const char* const kOrgans[] = {"liver", "appendectomy"};

void BM_OrganAccuracy(benchmark::State& state) {
  const std::string organ = kOrgans[state.range(0)];
  const int level = static_cast<int>(state.range(1));
  const std::string dir = std::string(SEROSA_SOURCE_DIR) + "/assets/";
  const TriMesh coarse = rest_boundary(read_mesh(dir + organ + "_coarse.msh"));
  const TriMesh fine = rest_boundary(read_mesh(dir + organ + "_fine.msh"));
  const std::vector<float> nrm = compute_vertex_normals(coarse.pos, coarse.tri);
  const SurfaceDistance dist(fine);
  TriMesh m;
  for (auto _ : state) {
    m = phong_tessellate(coarse.pos, nrm, coarse.tri, level, 0.75f);
    benchmark::DoNotOptimize(m.pos.data());
  }
  // Samples: every tessellated vertex and triangle centroid.
  const MeshDistance d = mesh_distance(m, dist);
  state.counters["input_triangles"] = static_cast<double>(coarse.tri.size() / 3);
  state.counters["reference_triangles"] = static_cast<double>(fine.tri.size() / 3);
  state.counters["drawn_triangles"] = static_cast<double>(m.tri.size() / 3);
  state.counters["max_dist_mm"] = 1e3 * d.max_m;
  state.counters["mean_dist_mm"] = 1e3 * d.mean_m;
  state.SetLabel(organ);
}
BENCHMARK(BM_OrganAccuracy)
    ->ArgsProduct({{0, 1}, {1, 2, 3, 4, 6}})
    ->ArgNames({"organ", "level"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace serosa::render

BENCHMARK_MAIN();
