// Rendering benchmarks (docs/BENCHMARKS.md "Rendering"):
//  - BM_FrameTime: one frame of the visual view (Phong tessellation, 640 x 480, 4x MSAA) through
//    EGL, against the tessellation level (1..6) and the surface size (icospheres of 20 * 4^k
//    triangles). The GL renderer is whatever EGL gives: Mesa llvmpipe (CPU) on the dev VM; the
//    benchmark's label names it.
//  - BM_PhongAccuracy: how far the tessellated surface is from the true sphere that a coarse
//    icosphere with exact (radial) normals approximates, against the level; computed on the CPU
//    with the shader's formula (render/phong_tessellation.h). BM_RefinedAccuracy gives the same
//    for flat, finer icospheres of equal triangle counts, for comparison.
//  - BM_OrganAccuracy: the same question on the bundled organs: the boundary of the coarse mesh
//    (assets/<organ>_coarse.msh, area-weighted vertex normals), Phong-tessellated, against the
//    boundary of the fine mesh of the same organ (<organ>_fine.msh) as the finer reference:
//    distance from every tessellated vertex and triangle centroid to the nearest fine triangle.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <unordered_map>

#include "engine/mesh_io.h"

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/phong_tessellation.h"
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
  ctx.bind_framebuffer();
  r.draw(f, o, kWidth, kHeight);  // warm-up: uploads indices, compiles the pipeline
  ctx.finish();
  for (auto _ : state) {
    ctx.bind_framebuffer();
    r.draw(f, o, kWidth, kHeight);
    ctx.finish();
  }
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

// Sphere of radius 1 from icosphere(subdiv) with radial normals, tessellated at `level`.
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

using V3 = std::array<double, 3>;

V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// The boundary of a tet mesh at rest: faces of one tet only, oriented away from the tet's fourth
// node; positions of all nodes (unused ones are harmless).
TriMesh boundary(const TetMesh& m) {
  std::map<std::array<std::int32_t, 3>, std::pair<int, std::array<std::int32_t, 4>>> faces;
  constexpr std::array<std::array<int, 4>, 4> kFaces{
      {{1, 2, 3, 0}, {0, 3, 2, 1}, {0, 1, 3, 2}, {0, 2, 1, 3}}};
  for (const Tet& t : m.tets)
    for (const auto& f : kFaces) {
      std::array<std::int32_t, 3> key{t[f[0]], t[f[1]], t[f[2]]};
      std::sort(key.begin(), key.end());
      auto& e = faces[key];
      ++e.first;
      e.second = {t[f[0]], t[f[1]], t[f[2]], t[f[3]]};
    }
  TriMesh out;
  for (const Vec3& p : m.rest)
    for (int k = 0; k < 3; ++k) out.pos.push_back(static_cast<float>(p[k]));
  for (const auto& [key, e] : faces) {
    if (e.first != 1) continue;
    auto [a, b, c, d] = e.second;
    const Vec3 n =
        (m.rest[static_cast<std::size_t>(b)] - m.rest[static_cast<std::size_t>(a)])
            .cross(m.rest[static_cast<std::size_t>(c)] - m.rest[static_cast<std::size_t>(a)]);
    if (n.dot(m.rest[static_cast<std::size_t>(d)] - m.rest[static_cast<std::size_t>(a)]) > 0.0)
      std::swap(b, c);
    for (const std::int32_t v : {a, b, c}) out.tri.push_back(static_cast<std::uint32_t>(v));
  }
  return out;
}

// Squared distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
double dist2_to_triangle(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto at = [&](double v, double w) {
    V3 q{a[0] + v * ab[0] + w * ac[0], a[1] + v * ab[1] + w * ac[1], a[2] + v * ab[2] + w * ac[2]};
    const V3 d = sub(p, q);
    return dot(d, d);
  };
  if (d1 <= 0 && d2 <= 0) return dot(ap, ap);
  const V3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(d1 / (d1 - d3), 0);
  const V3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double den = 1.0 / (va + vb + vc);
  return at(vb * den, vc * den);
}

// Nearest-triangle distances to a fixed triangle mesh through a uniform grid of its triangles'
// boxes; a query searches growing shells of cells until no closer triangle can exist.
class SurfaceDistance {
 public:
  explicit SurfaceDistance(const TriMesh& m) : m_(m) {
    const std::size_t t = m.tri.size() / 3;
    lo_ = {1e30, 1e30, 1e30};
    V3 hi{-1e30, -1e30, -1e30};
    double edge = 0.0;
    for (std::size_t f = 0; f < t; ++f)
      for (int k = 0; k < 3; ++k) {
        const V3 p = point(m.tri[3 * f + k]);
        const V3 q = point(m.tri[3 * f + (k + 1) % 3]);
        edge += std::sqrt(dot(sub(p, q), sub(p, q)));
        for (int d = 0; d < 3; ++d) {
          lo_[d] = std::min(lo_[d], p[d]);
          hi[d] = std::max(hi[d], p[d]);
        }
      }
    cell_ = 2.0 * edge / static_cast<double>(3 * std::max<std::size_t>(t, 1));
    for (std::size_t f = 0; f < t; ++f) {
      std::array<std::int64_t, 3> a{}, b{};
      for (int d = 0; d < 3; ++d) {
        double mn = 1e30, mx = -1e30;
        for (int k = 0; k < 3; ++k) {
          const double c = point(m.tri[3 * f + k])[static_cast<std::size_t>(d)];
          mn = std::min(mn, c);
          mx = std::max(mx, c);
        }
        a[d] = cell_of(mn, d);
        b[d] = cell_of(mx, d);
      }
      for (std::int64_t i = a[0]; i <= b[0]; ++i)
        for (std::int64_t j = a[1]; j <= b[1]; ++j)
          for (std::int64_t k = a[2]; k <= b[2]; ++k)
            grid_[key(i, j, k)].push_back(static_cast<std::uint32_t>(f));
    }
  }

  [[nodiscard]] double operator()(const V3& p) const {
    const std::array<std::int64_t, 3> c{cell_of(p[0], 0), cell_of(p[1], 1), cell_of(p[2], 2)};
    double best = 1e300;
    for (std::int64_t r = 0; r < 64; ++r) {
      for (std::int64_t i = -r; i <= r; ++i)
        for (std::int64_t j = -r; j <= r; ++j)
          for (std::int64_t k = -r; k <= r; ++k) {
            if (std::max({std::abs(i), std::abs(j), std::abs(k)}) != r) continue;  // the shell
            const auto it = grid_.find(key(c[0] + i, c[1] + j, c[2] + k));
            if (it == grid_.end()) continue;
            for (const std::uint32_t f : it->second)
              best = std::min(best,
                              dist2_to_triangle(p, point(m_.tri[3 * f]), point(m_.tri[3 * f + 1]),
                                                point(m_.tri[3 * f + 2])));
          }
      // Cells beyond shell r are at least r * cell away.
      if (best < 1e300 && std::sqrt(best) <= static_cast<double>(r) * cell_) break;
    }
    return std::sqrt(best);
  }

 private:
  [[nodiscard]] V3 point(std::uint32_t v) const {
    return {static_cast<double>(m_.pos[3 * v]), static_cast<double>(m_.pos[3 * v + 1]),
            static_cast<double>(m_.pos[3 * v + 2])};
  }
  [[nodiscard]] std::int64_t cell_of(double x, int d) const {
    return static_cast<std::int64_t>(std::floor((x - lo_[static_cast<std::size_t>(d)]) / cell_));
  }
  static std::int64_t key(std::int64_t i, std::int64_t j, std::int64_t k) {
    return ((i + 4096) << 42) | ((j + 4096) << 21) | (k + 4096);
  }
  const TriMesh& m_;
  V3 lo_{};
  double cell_ = 1.0;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid_;
};

const char* const kOrgans[] = {"liver", "appendectomy"};

void BM_OrganAccuracy(benchmark::State& state) {
  const std::string organ = kOrgans[state.range(0)];
  const int level = static_cast<int>(state.range(1));
  const std::string dir = std::string(SEROSA_SOURCE_DIR) + "/assets/";
  const TriMesh coarse = boundary(read_mesh(dir + organ + "_coarse.msh"));
  const TriMesh fine = boundary(read_mesh(dir + organ + "_fine.msh"));
  const std::vector<float> nrm = compute_vertex_normals(coarse.pos, coarse.tri);
  const SurfaceDistance dist(fine);
  TriMesh m;
  for (auto _ : state) {
    m = phong_tessellate(coarse.pos, nrm, coarse.tri, level, 0.75f);
    benchmark::DoNotOptimize(m.pos.data());
  }
  // Samples: every tessellated vertex and triangle centroid.
  double max_d = 0.0, sum_d = 0.0;
  std::size_t n = 0;
  auto sample = [&](const V3& p) {
    const double d = dist(p);
    max_d = std::max(max_d, d);
    sum_d += d;
    ++n;
  };
  for (std::size_t v = 0; v < m.pos.size() / 3; ++v)
    sample({static_cast<double>(m.pos[3 * v]), static_cast<double>(m.pos[3 * v + 1]),
            static_cast<double>(m.pos[3 * v + 2])});
  for (std::size_t f = 0; f < m.tri.size() / 3; ++f) {
    V3 c{};
    for (int k = 0; k < 3; ++k)
      for (int d = 0; d < 3; ++d)
        c[static_cast<std::size_t>(d)] +=
            static_cast<double>(m.pos[3 * m.tri[3 * f + k] + d]) / 3.0;
    sample(c);
  }
  state.counters["input_triangles"] = static_cast<double>(coarse.tri.size() / 3);
  state.counters["reference_triangles"] = static_cast<double>(fine.tri.size() / 3);
  state.counters["drawn_triangles"] = static_cast<double>(m.tri.size() / 3);
  state.counters["max_dist_mm"] = 1e3 * max_d;
  state.counters["mean_dist_mm"] = 1e3 * sum_d / static_cast<double>(std::max<std::size_t>(n, 1));
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
