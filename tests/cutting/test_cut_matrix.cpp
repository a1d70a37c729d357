// The property-test matrix of the cutter on structured grids (exact coplanar nodes, edges and
// faces) and jittered grids: per family of cuts, many random cuts, every invariant on every
// one (cutting/validate.h; covering cuts also separate the mesh and split its volume exactly),
// and the numbers that say what the cuts cost the mesh: tets created per cut and the minimum
// element quality (engine/mesh_quality.h mean ratio) after the cuts, per family.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include "cut_helpers.h"
#include "mesh_fixtures.h"

namespace serosa::cutting {
namespace {

using testing::Applied;
using testing::cut_and_check;
using testing::problems;
using testing::square;

enum Family {
  kGeneral,
  kAxisAligned,
  kThroughNode,
  kAlongEdge,
  kInFacePlane,
  kPartial,
  kTipOnNode,
  kRepeated,
  kCrossing,
  kNearParallel,
  kNumFamilies
};
constexpr std::array<const char*, kNumFamilies> kNames{
    "general", "axis-aligned",  "through a node", "along an edge", "in a face's plane",
    "partial", "tip on a node", "repeated plane", "crossing",      "near-parallel 1e-6 L"};

struct Tally {
  int cuts = 0;
  std::int64_t created = 0;  ///< tets added, over all cuts
  std::int64_t net_max = 0;  ///< most tets added less removed by one cut
  double min_quality = 1.0;
};

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    const Vec3 n(g(rng), g(rng), g(rng));
    if (n.norm() > 1e-3) return n.normalized();
  }
}

TEST(CutMatrix, EveryFamilyOnGridsAndJitteredGrids) {
#if defined(__SANITIZE_ADDRESS__)
  const int per_family = 12;
#else
  const int per_family = 40;
#endif
  const TetMesh exact = test_meshes::kuhn_cube(4);
  const TetMesh jittered = test_meshes::kuhn_cube(4, 1.0, 0.2, 17);
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(0.2, 3.8), ang(0.0, 6.283185307179586), sz(0.3, 1.5);
  std::array<Tally, kNumFamilies> tally{};
  for (int fam = 0; fam < kNumFamilies; ++fam)
    for (int i = 0; i < 2 * per_family; ++i) {
      const TetMesh& m = i % 2 == 0 ? exact : jittered;
      const Tet& t = m.tets[static_cast<std::size_t>(rng() % m.tets.size())];
      const std::int32_t node = t[rng() % 4];
      Vec3 n = random_unit(rng);
      Vec3 c(u(rng), u(rng), u(rng));
      bool covering = true;
      std::optional<ConvexPolygon> blade;
      switch (fam) {
        case kAxisAligned:
          n = Vec3::Unit(static_cast<int>(rng() % 3));
          if (i % 4 < 2) c = Vec3::Constant(static_cast<double>(1 + rng() % 3));  // grid planes
          break;
        case kThroughNode:
          c = m.x[static_cast<std::size_t>(node)];
          break;
        case kAlongEdge: {
          const std::int32_t other = t[(std::find(t.begin(), t.end(), node) - t.begin() + 1) % 4];
          const Vec3 e = m.x[static_cast<std::size_t>(other)] - m.x[static_cast<std::size_t>(node)];
          n = e.cross(random_unit(rng)).normalized();
          c = m.x[static_cast<std::size_t>(node)];
          break;
        }
        case kInFacePlane: {
          const Vec3 &a = m.x[static_cast<std::size_t>(t[0])],
                     &b = m.x[static_cast<std::size_t>(t[1])],
                     &d = m.x[static_cast<std::size_t>(t[2])];
          n = (b - a).cross(d - a).normalized();
          c = a;
          break;
        }
        case kPartial:
        case kTipOnNode: {
          covering = false;
          const Vec3 a0 = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
          const Vec3 e1 = (a0 - n * n.dot(a0)).normalized(), e2 = n.cross(e1);
          const Vec3 tip = fam == kTipOnNode ? m.x[static_cast<std::size_t>(node)] : c;
          const double ph = ang(rng);
          blade = ConvexPolygon::make(
              {tip, tip + sz(rng) * (std::cos(ph) * e1 + std::sin(ph) * e2),
               tip + sz(rng) * (std::cos(ph + 1.2) * e1 + std::sin(ph + 1.2) * e2)});
          break;
        }
        default:
          break;
      }
      if (!blade) blade = square(n, c, 100.0, ang(rng));
      if (!blade) continue;
      // Sequences: the family's second cut acts on the result of a first one.
      TetMesh base = m;
      if (fam == kRepeated || fam == kCrossing || fam == kNearParallel) {
        const Applied first = cut_and_check(m, *blade, true);
        ASSERT_TRUE(first.report.ok) << kNames[fam] << " " << i << "\n" << problems(first.report);
        base = first.after;
        if (fam == kCrossing) blade = square(random_unit(rng), Vec3(u(rng), u(rng), u(rng)), 100.0);
        if (fam == kNearParallel) {
          const Vec3 shift = 4e-6 * blade->normal();  // 1e-6 of the mesh size (4)
          std::vector<Vec3> pts;
          for (const Vec3& p : blade->points()) pts.push_back(p + shift);
          blade = ConvexPolygon(pts);
        }
      }
      const Applied a = cut_and_check(base, *blade, covering);
      ASSERT_TRUE(a.report.ok) << kNames[fam] << " case " << i << "\n" << problems(a.report);
      ASSERT_EQ(a.result.stats.degenerate_tets, 0) << kNames[fam] << " case " << i;
      if (!covering) {
        EXPECT_EQ(count_components(a.after), count_components(base)) << i;
      }
      Tally& tl = tally[static_cast<std::size_t>(fam)];
      ++tl.cuts;
      tl.created += a.result.stats.tets_added;
      tl.net_max = std::max(tl.net_max, a.result.stats.tets_added - a.result.stats.tets_removed);
      tl.min_quality = std::min(tl.min_quality, a.report.min_quality);
    }
  std::printf("%-20s %6s %14s %12s %12s\n", "family (4^3 grids)", "cuts", "tets created", "net max",
              "min quality");
  for (int fam = 0; fam < kNumFamilies; ++fam) {
    const Tally& tl = tally[static_cast<std::size_t>(fam)];
    std::printf("%-20s %6d %14.1f %12lld %12.3g\n", kNames[fam], tl.cuts,
                static_cast<double>(tl.created) / std::max(tl.cuts, 1),
                static_cast<long long>(tl.net_max), tl.min_quality);
    EXPECT_GE(tl.cuts, per_family) << kNames[fam];
    EXPECT_GT(tl.min_quality, 0.0) << kNames[fam];
    std::string key = "tets_created_per_cut_";
    key.append(std::to_string(fam));
    RecordProperty(key, std::to_string(static_cast<double>(tl.created) / std::max(tl.cuts, 1)));
    key = "min_quality_";
    key.append(std::to_string(fam));
    RecordProperty(key, std::to_string(tl.min_quality));
  }
}

}  // namespace
}  // namespace serosa::cutting
