// app::Simulation, the driver `serosa headless` runs and Python wraps: stepping it equals
// run_headless bit for bit; a cut it is asked for goes through the cutting stage (rest volume
// conserved, handed on like a stroke's); a damaged snapshot leaves the run as it was; only tools
// whose device is "python" take a pose from outside.
#include <gtest/gtest.h>

#include <stdexcept>

#include "app/headless.h"
#include "app/simulation.h"
#include "app_test_util.h"
#include "engine/input_error.h"
#include "engine/sim_state.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

HeadlessOptions transection(std::int64_t steps) {
  HeadlessOptions o;
  o.scene = source("config/transection.toml");
  o.steps = steps;
  o.progress = false;
  o.scene_record = false;
  return o;
}

double rest_volume(const TetMesh& m) {
  double v = 0.0;
  for (std::int32_t t = 0; t < m.num_tets(); ++t) v += m.rest_volume(t);
  return v;
}

TEST(Simulation, SteppingItEqualsTheHeadlessRun) {
  const auto report = run_headless(transection(40));
  Simulation sim(transection(40));
  for (int i = 0; i < 40; ++i) sim.step();
  EXPECT_EQ(hash_hex(state_hash(sim.state())), report.at("state_hash"));
  EXPECT_EQ(sim.report().at("state_hash"), report.at("state_hash"));
  EXPECT_EQ(sim.finish().at("steps_taken"), 40);
}

TEST(Simulation, AnAskedCutGoesThroughTheCuttingStageAndConservesVolume) {
  Simulation sim(transection(10));
  sim.step();
  const double before = rest_volume(sim.state().mesh);
  // Across the whole organ at its middle: a square larger than it, normal along x.
  Vec3 lo = sim.state().mesh.rest[0], hi = lo;
  for (const Vec3& p : sim.state().mesh.rest) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double x = 0.5 * (lo.x() + hi.x());
  const cutting::ConvexPolygon square({{x, lo.y() - 0.01, lo.z() - 0.01},
                                       {x, hi.y() + 0.01, lo.z() - 0.01},
                                       {x, hi.y() + 0.01, hi.z() + 0.01},
                                       {x, lo.y() - 0.01, hi.z() + 0.01}});
  const cutting::StrokeReport r = sim.cut(square);
  EXPECT_EQ(r.cuts, 1u);
  EXPECT_GT(r.tets_created, r.tets_crossed);
  ASSERT_EQ(sim.state().events.cuts.size(), 1u);
  EXPECT_EQ(sim.state().events.cuts[0].tool, kNoTool);
  EXPECT_NEAR(rest_volume(sim.state().mesh), before, 1e-12 * before);
  EXPECT_THROW((void)sim.snapshot(), std::logic_error);  // the cut is in flight
  sim.step();
  EXPECT_NO_THROW((void)sim.snapshot());
  EXPECT_EQ(sim.report().at("cutting").at("tets_added"), r.tets_created);
}

TEST(Simulation, ADamagedSnapshotLeavesTheRunAsItWas) {
  Simulation sim(transection(10));
  for (int i = 0; i < 5; ++i) sim.step();
  const auto hash = state_hash(sim.state());
  std::vector<std::uint8_t> bytes = sim.snapshot();
  bytes.resize(bytes.size() / 2);
  EXPECT_THROW(sim.restore(bytes, "half a snapshot"), InputError);
  EXPECT_EQ(state_hash(sim.state()), hash);
  EXPECT_EQ(sim.state().step, 5u);
  sim.step();  // and it goes on
  EXPECT_EQ(sim.state().step, 6u);
}

TEST(Simulation, OnlyAPythonToolTakesAPoseFromOutside) {
  HeadlessOptions o = transection(3);
  EXPECT_THROW(Simulation(o).set_tool(0, ToolState{}), std::invalid_argument);
  o.overrides.push_back(parse_override("tool.0.device=\"python\"", "test"));
  Simulation sim(o);
  ToolState t;
  t.tip_m = {0.01, 0.02, 0.03};
  t.jaw_rad = 0.25;
  sim.set_tool(0, t);
  sim.step();
  EXPECT_EQ(sim.state().tools[0].tip_m, t.tip_m);
  EXPECT_EQ(sim.state().tools[0].jaw_rad, 0.25);
  EXPECT_GT(sim.state().tools[0].tick, 0u);
}

}  // namespace
}  // namespace serosa::app
