// `serosa cut` end to end (docs/ARCHITECTURE.md "External contracts"): runs the built executable on
// the bundled beam (assets/beam_coarse.msh: 0.1 x 0.01 x 0.01 m, x in [0, 0.1], 20 x 2 x 2 cubes of
// 5 mm) and checks the exit code, the JSON summary and the Gmsh 2.2 file it writes, for each
// method, and that bad --polygon and --method values exit 1 naming the flag and the value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app_test_util.h"
#include "cutting/validate.h"
#include "engine/io/mesh_io.h"
#include "engine/mesh_check.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;
using testing::CliResult;
using testing::out_dir;
using testing::run_serosa;
using testing::source;

// A square in the plane x = X (a little tilted when tilt != 0) that covers the beam's section.
std::string covering(double x, double tilt = 0.0) {
  std::string s;
  for (const auto& [y, z] : {std::pair{-0.02, -0.02}, {0.02, -0.02}, {0.02, 0.02}, {-0.02, 0.02}}) {
    if (!s.empty()) s.append(" ");
    s.append(std::to_string(x + tilt * y)).append(",").append(std::to_string(y));
    s.append(",").append(std::to_string(z));
  }
  return "'" + s + "'";
}

struct CutRun {
  CliResult cli;
  nlohmann::json summary;
  TetMesh out;
};

CutRun cut(const std::string& name, const std::string& flags) {
  const fs::path dir = out_dir("cli_cut_" + name);
  const fs::path out = dir / "out.msh";
  CutRun r;
  r.cli = run_serosa("cut '" + source("assets/beam_coarse.msh").string() + "' " + flags +
                     " --out '" + out.string() + "' --json");
  if (r.cli.code != 0) return r;
  r.summary = nlohmann::json::parse(r.cli.out);
  r.out = read_mesh(out);
  return r;
}

TEST(CliCut, PatternCoveringCutSplitsTheBeamInTwoAndKeepsVolume) {
  const CutRun r = cut("pattern", "--polygon " + covering(0.0523, 0.3));
  ASSERT_EQ(r.cli.code, 0) << r.cli.out;
  const auto& before = r.summary.at("before");
  const auto& after = r.summary.at("after");
  EXPECT_EQ(r.summary.at("method").get<std::string>(), "pattern");
  EXPECT_EQ(before.at("tets").get<int>(), 480);
  EXPECT_GT(after.at("tets").get<int>(), 480);
  EXPECT_GT(after.at("nodes").get<int>(), before.at("nodes").get<int>());
  EXPECT_GT(r.summary.at("tets_created").get<int>(), 0);
  const double v0 = before.at("volume_m3").get<double>();
  EXPECT_NEAR(v0, 1e-5, 1e-15);
  EXPECT_NEAR(after.at("volume_m3").get<double>(), v0, 1e-12 * v0);
  EXPECT_GT(after.at("min_quality").get<double>(), 0.0);
  ASSERT_EQ(r.summary.at("cuts").size(), 1U);
  EXPECT_GE(r.summary.at("cuts")[0].at("time_ms").get<double>(), 0.0);
  // The file: the cut mesh, valid, in two pieces, every tet still group 1.
  EXPECT_EQ(r.out.num_tets(), after.at("tets").get<int>());
  EXPECT_TRUE(check_mesh(r.out).valid);
  EXPECT_EQ(cutting::count_components(r.out), 2);
  for (std::uint16_t g : r.out.group) EXPECT_EQ(g, 1);
}

TEST(CliCut, SeveralPolygonsApplyInTurn) {
  const CutRun r =
      cut("two", "--polygon " + covering(0.0311, -0.2) + " --polygon " + covering(0.0712, 0.1));
  ASSERT_EQ(r.cli.code, 0) << r.cli.out;
  EXPECT_EQ(r.summary.at("cuts").size(), 2U);
  EXPECT_EQ(cutting::count_components(r.out), 3);
  const double v0 = r.summary.at("before").at("volume_m3").get<double>();
  EXPECT_NEAR(r.summary.at("after").at("volume_m3").get<double>(), v0, 1e-12 * v0);
}

TEST(CliCut, RemoveLosesVolumeSnapKeepsIt) {
  const CutRun rm = cut("remove", "--method remove --polygon " + covering(0.0523));
  ASSERT_EQ(rm.cli.code, 0) << rm.cli.out;
  const double v0 = rm.summary.at("before").at("volume_m3").get<double>();
  // The plane x = 0.0523 lies in the column of cubes x in [0.05, 0.055]: its 4 cubes go.
  EXPECT_NEAR(rm.summary.at("after").at("volume_m3").get<double>(), v0 - 4 * 0.005 * 0.005 * 0.005,
              1e-12 * v0);
  EXPECT_EQ(rm.summary.at("after").at("tets").get<int>(), 480 - 24);
  EXPECT_EQ(rm.summary.at("tets_created").get<int>(), 0);
  EXPECT_EQ(cutting::count_components(rm.out), 2);

  const CutRun sn = cut("snap", "--method snap --polygon " + covering(0.0523));
  ASSERT_EQ(sn.cli.code, 0) << sn.cli.out;
  EXPECT_EQ(sn.summary.at("after").at("tets").get<int>(), 480);  // snapping never subdivides
  EXPECT_NEAR(sn.summary.at("after").at("volume_m3").get<double>(), v0, 1e-12 * v0);
  EXPECT_EQ(cutting::count_components(sn.out), 2);
  EXPECT_TRUE(check_mesh(sn.out).valid);
}

TEST(CliCut, NegativeCoordinatesParse) {
  const CutRun r = cut("negative", "--polygon '-0.02,-0.02,-0.02 -0.02,0.02,-0.02 0.09,0.02,0.02'");
  ASSERT_EQ(r.cli.code, 0) << r.cli.out;
  EXPECT_GT(r.summary.at("after").at("tets").get<int>(), 480);
}

// A scissors blade hinged beside the beam, closing in 20 thin steps in a tilted plane (n) across
// the section at x ~ 0.05: the triangles (hinge, tip before, tip after), full precision.
std::string fan_flags() {
  const Vec3 n = Vec3(1.0, 0.15, -0.1).normalized(), hinge(0.0523, -0.011, 0.001);
  const Vec3 a = n.unitOrthogonal(), b = n.cross(a);
  auto tip = [&](double t) -> Vec3 { return hinge + 0.03 * (std::cos(t) * a + std::sin(t) * b); };
  auto point = [](const Vec3& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g", p.x(), p.y(), p.z());
    return std::string(buf);
  };
  std::string flags;
  const int steps = 20;
  for (int k = 0; k < steps; ++k) {
    const double s0 = 2.0 * (0.5 - static_cast<double>(k) / steps);
    const double s1 = 2.0 * (0.5 - static_cast<double>(k + 1) / steps);
    flags += " --polygon '" + point(hinge) + " " + point(tip(1.5 * s0)) + " " +
             point(tip(1.5 * s1)) + "'";
  }
  return flags;
}

// --stroke: the 20 steps are one progressive stroke; the beam separates, every step after the
// first extends the stroke, volume is kept, and the released nodes are not written.
TEST(CliCut, StrokeOfThinStepsCutsTheBeamThrough) {
  const CutRun r = cut("stroke", "--stroke" + fan_flags());
  ASSERT_EQ(r.cli.code, 0) << r.cli.out;
  EXPECT_TRUE(r.summary.at("stroke").get<bool>());
  ASSERT_EQ(r.summary.at("cuts").size(), 20U);
  for (std::size_t k = 1; k < 20; ++k)
    EXPECT_TRUE(r.summary.at("cuts")[k].at("extends_stroke").get<bool>()) << k;
  EXPECT_EQ(cutting::count_components(r.out), 2);
  const MeshCheckReport mc = check_mesh(r.out);
  EXPECT_TRUE(mc.valid);
  EXPECT_EQ(mc.unreferenced_nodes, 0);
  EXPECT_EQ(r.out.num_nodes(), r.summary.at("after").at("nodes").get<int>());
  // Tets created: the stroke's pieces at its end (one cut of the sector), not the sum of the
  // steps' deltas.
  const int created = r.summary.at("tets_created").get<int>();
  EXPECT_GE(created, r.out.num_tets() - r.summary.at("before").at("tets").get<int>());
  EXPECT_LE(created, r.out.num_tets());
  const double v0 = r.summary.at("before").at("volume_m3").get<double>();
  EXPECT_NEAR(r.summary.at("after").at("volume_m3").get<double>(), v0, 1e-12 * v0);
}

// Bad flags: exit 1, the message names the flag and the offending value.
void expect_rejected(const std::string& flags, const std::string& needle) {
  const fs::path out = out_dir("cli_cut_bad") / "out.msh";
  const CliResult r = run_serosa("cut '" + source("assets/beam_coarse.msh").string() + "' " +
                                 flags + " --out '" + out.string() + "'");
  EXPECT_EQ(r.code, 1) << flags << "\n" << r.out;
  EXPECT_NE(r.out.find(needle), std::string::npos) << flags << "\n" << r.out;
  EXPECT_FALSE(fs::exists(out)) << flags;
}

TEST(CliCut, BadPolygonsExitOneNamingFlagAndValue) {
  expect_rejected("--polygon '0,0,0 1,0,0'", "--polygon #1 \"0,0,0 1,0,0\": has 2 point(s)");
  expect_rejected("--polygon '0,0,0 1,0,x 0,1,0'", "\"x\" is not a finite number");
  expect_rejected("--polygon '0,0,0 1,0 0,1,0'", "exactly three comma-separated");
  expect_rejected("--polygon '0,0,0 1,0,0,5 0,1,0'", "exactly three comma-separated");
  expect_rejected("--polygon '0,0,0 1,0,0 0,1,0 1,1,0.5'", "--polygon #1");  // not planar
  expect_rejected("--polygon '0,0,0 1,0,0 0,1,0 1,1,0'", "not a valid blade polygon");  // crossed
  expect_rejected("--polygon '0,0,0 1,0,0 2,0,0'", "not a valid blade polygon");        // no area
  expect_rejected("--polygon " + covering(0.05) + " --polygon '0,0,0 1,0,nan 0,1,0'",
                  "--polygon #2");
  expect_rejected("--polygon " + covering(0.05) + " --method chop", "--method \"chop\"");
  expect_rejected("--polygon " + covering(0.05) + " --method remove --stroke",
                  "--stroke with --method \"remove\"");
}

// A bad --out is found before any cut runs (exit 1, naming the flag), and an existing file there
// is left as it was.
TEST(CliCut, BadOutExitsOneBeforeCutting) {
  const fs::path dir = out_dir("cli_cut_bad_out");
  for (const std::string& bad : {(dir / "no_such_dir" / "out.msh").string(), dir.string()}) {
    const CliResult r = run_serosa("cut '" + source("assets/beam_coarse.msh").string() +
                                   "' --polygon " + covering(0.05) + " --out '" + bad + "'");
    EXPECT_EQ(r.code, 1) << bad << "\n" << r.out;
    EXPECT_NE(r.out.find("--out " + bad), std::string::npos) << r.out;
  }
}

// A missing argument or an unknown flag is bad input like any other: exit 1 (not CLI11's own
// codes), with the parser's message; --help exits 0.
TEST(CliCut, ArgumentErrorsExitOne) {
  std::string mesh = "'";
  mesh.append(source("assets/beam_coarse.msh").string()).append("'");
  std::string out = " --out '";
  out.append((out_dir("cli_cut_args") / "o.msh").string()).append("'");
  std::vector<std::string> cases(3, "cut ");
  cases[0].append(out);                                                // no mesh, no polygon
  cases[1].append(mesh).append(out);                                   // no polygon
  cases[2].append(mesh).append(" --polygon ").append(covering(0.05));  // an unknown flag
  cases[2].append(out).append(" --frobnicate");
  for (const std::string& args : cases) {
    const CliResult r = run_serosa(args);
    EXPECT_EQ(r.code, 1) << args << "\n" << r.out;
    EXPECT_FALSE(r.out.empty()) << args;
  }
  EXPECT_EQ(run_serosa("cut --help").code, 0);
}

// A polygon that changes nothing (it misses the mesh, or lies beside it) is said, in the JSON
// summary's "warnings" and on stderr, not silently written as an unchanged mesh.
TEST(CliCut, PolygonThatChangesNothingIsWarned) {
  const CutRun far = cut("misses", "--polygon '5,5,5 6,5,5 6,6,5'");
  ASSERT_EQ(far.cli.code, 0) << far.cli.out;
  ASSERT_EQ(far.summary["warnings"].size(), 1u);
  EXPECT_NE(far.summary["warnings"][0].get<std::string>().find("polygon 1 changed nothing"),
            std::string::npos);
  EXPECT_EQ(far.summary["after"]["tets"], far.summary["before"]["tets"]);
  const CutRun hit = cut("hits", "--polygon " + covering(0.05));
  ASSERT_EQ(hit.cli.code, 0) << hit.cli.out;
  EXPECT_TRUE(hit.summary["warnings"].empty());
}

}  // namespace
}  // namespace serosa::app
