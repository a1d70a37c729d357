// `serosa bench` parts cutting, surface, tessellation and haptics (bench/suite/part_*.cpp), each
// run with quick = true: the tables' shapes, the plots and checks naming real columns, every
// monotone check holding, the CSV files written, and the physics each part claims.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "app_test_util.h"
#include "bench/suite/bench_parts.h"
#include "surface/extract_surface.h"

namespace serosa::bench {
namespace {

namespace fs = std::filesystem;

BenchOptions quick_options(const std::string& name) {
  BenchOptions o;
  o.quick = true;
  o.out = app::testing::out_dir("bench_parts_b_" + name);
  o.assets_dir = app::testing::source("assets");
  return o;
}

const Table& table(const PartResult& r, const std::string& name) {
  const auto it = std::find_if(r.tables.begin(), r.tables.end(),
                               [&](const Table& t) { return t.name == name; });
  if (it == r.tables.end()) throw std::invalid_argument("no table " + name);
  return *it;
}

bool has_table(const PartResult& r, const std::string& name) {
  return std::any_of(r.tables.begin(), r.tables.end(),
                     [&](const Table& t) { return t.name == name; });
}

/// Shapes, references and checks common to every part; writes the CSVs into options.out.
void expect_well_formed(const PartResult& r, const BenchOptions& o) {
  ASSERT_FALSE(r.tables.empty());
  ASSERT_FALSE(r.plots.empty());
  for (const Table& t : r.tables) {
    SCOPED_TRACE(t.name);
    EXPECT_FALSE(t.rows.empty());
    EXPECT_EQ(t.rows.size(), t.settings.size());
    for (const auto& row : t.rows) {
      ASSERT_EQ(row.size(), t.columns.size());
      for (const double v : row) EXPECT_TRUE(std::isfinite(v));
    }
    t.write_csv(o.out / (t.name + ".csv"));
    EXPECT_TRUE(fs::exists(o.out / (t.name + ".csv")));
  }
  for (const Plot& p : r.plots) {
    SCOPED_TRACE(p.name);
    EXPECT_FALSE(p.series.empty());
    for (const Series& s : p.series) {
      ASSERT_TRUE(has_table(r, s.table)) << s.table;
      EXPECT_NO_THROW((void)table(r, s.table).column(s.x));
      EXPECT_NO_THROW((void)table(r, s.table).column(s.y));
    }
  }
  for (const MonotoneCheck& c : r.checks) {
    ASSERT_TRUE(has_table(r, c.table)) << c.table;
    EXPECT_EQ(check_monotone(table(r, c.table), c), "") << c.why;
  }
}

TEST(BenchPartsB, CuttingPatternKeepsVolumeAndRemovalLosesIt) {
  const BenchOptions o = quick_options("cutting");
  const PartResult r = run_cutting_part(o);
  expect_well_formed(r, o);
  const Table& m = table(r, "cutting_methods");
  ASSERT_EQ(m.settings, (std::vector<std::string>{"pattern", "remove", "snap"}));
  const auto lost = m.values("volume_lost_rel");
  const auto max_dist = m.values("max_dist_mm");
  const auto created = m.values("tets_created");
  const auto quality = m.values("min_quality");
  EXPECT_LE(std::abs(lost[0]), 1e-12);  // pattern: exact volume
  EXPECT_GT(lost[1], 1e-4);             // removal drops every tet the blade touches
  EXPECT_LE(std::abs(lost[2]), 1e-12);  // snapping moves nodes inside the block: volume kept
  EXPECT_GT(created[0], 0.0);           // pattern subdivides
  EXPECT_LT(created[1], 0.0);           // removal only removes
  EXPECT_LT(max_dist[0], max_dist[1]);  // the pattern's cut follows the blade, removal's does not
  for (const double q : quality) EXPECT_GT(q, 0.0);
  const Table& blades = table(r, "cutting_blades");
  EXPECT_EQ(blades.rows.size(), 3 * 4u);
  for (const double v : blades.values("ms_per_cut")) EXPECT_GT(v, 0.0);
}

TEST(BenchPartsB, SurfaceMethodsAgreeAndOnlyTimeDiffers) {
  const BenchOptions o = quick_options("surface");
  const PartResult r = run_surface_part(o);  // throws when the surfaces differ
  expect_well_formed(r, o);
  const bool cuda = surface::cuda_available();
  EXPECT_EQ(has_table(r, "surface_full_cuda"), cuda);
  const Table& inc = table(r, "surface_incremental");
  ASSERT_EQ(inc.rows.size(), 2u);
  for (const char* name : {"surface_full_cpu_1thread", "surface_full_cpu_2threads"}) {
    const Table& t = table(r, name);
    EXPECT_EQ(t.values("tets"), inc.values("tets"));
    EXPECT_EQ(t.values("faces"), inc.values("faces"));
  }
  const auto tets = inc.values("tets");
  EXPECT_GT(tets[0], 6.0 * 8 * 8 * 8);  // the cuts subdivide tets
  EXPECT_GT(tets[1], 6.0 * 16 * 16 * 16);
}

TEST(BenchPartsB, TessellationSphereGetsCloserFromFlatAndCountsTriangles) {
  const BenchOptions o = quick_options("tessellation");
  const PartResult r = run_tessellation_part(o);
  expect_well_formed(r, o);
  const Table& s = table(r, "tessellation_sphere");
  ASSERT_EQ(s.rows.size(), 3u);
  const auto mean = s.values("mean_dist_rel");
  EXPECT_LT(mean[1], 0.5 * mean[0]);  // level 2 much closer to the sphere than flat
  const auto drawn = s.values("drawn_triangles");
  for (std::size_t i = 0; i < drawn.size(); ++i)
    EXPECT_EQ(drawn[i], 80.0 * static_cast<double>((i + 1) * (i + 1)));
  for (const char* organ : {"tessellation_liver", "tessellation_appendectomy"}) {
    const Table& t = table(r, organ);
    ASSERT_EQ(t.rows.size(), 3u);
    for (const double d : t.values("max_dist_mm")) {
      EXPECT_GT(d, 0.0);
      EXPECT_LT(d, 10.0);  // the coarse organ is within a centimetre of the fine one
    }
    for (const double ms : t.values("ms_per_frame")) EXPECT_GT(ms, 0.0);
  }
}

TEST(BenchPartsB, HapticsErrorFallsAndStabilityIsLostNearColgatesBound) {
  const BenchOptions o = quick_options("haptics");
  const PartResult r = run_haptics_part(o);
  expect_well_formed(r, o);
  ASSERT_EQ(r.checks.size(), 2u);  // both checks (error and margin fall) ran above
  const Table& t = table(r, "haptics_stiffness");
  const auto k = t.values("coupling_Npm");
  const auto err = t.values("force_error_rel");
  const auto decay = t.values("decay_per_s");
  const auto pen = t.values("wall_penetration_mm");
  ASSERT_GE(k.size(), 4u);
  for (std::size_t i = 0; i < k.size(); ++i) {
    SCOPED_TRACE(k[i]);
    // Series coupling with tissue of 1000 N/m: error k_t / (k_c + k_t) while the lag is small.
    if (k[i] <= 1000.0) {
      EXPECT_NEAR(err[i], 1000.0 / (k[i] + 1000.0), 0.03);
    }
    // Static wall penetration of a 3 N push: 3 / k_c.
    EXPECT_NEAR(pen[i], 3e3 / k[i], 0.02 * 3e3 / k[i]);
    // Colgate & Schenkel: passive below 2 b / T = 4000 N/m; the tap decays below, grows above.
    if (k[i] <= 0.75 * 4000.0) {
      EXPECT_GT(decay[i], 0.0);
    }
    if (k[i] >= 1.25 * 4000.0) {
      EXPECT_LT(decay[i], 0.0);
    }
  }
  // A soft coupling: the decay rate approaches b / (2 m) = 10 / s of the continuous system.
  EXPECT_NEAR(decay[0], 10.0, 1.0);
}

}  // namespace
}  // namespace serosa::bench
