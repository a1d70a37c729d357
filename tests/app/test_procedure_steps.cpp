// The appendectomy's steps (metrics/procedure_steps.h) on a block with the procedure's anatomy:
// a base (x < 1 cm), a specimen along its top row beyond it, and a fold (the mesentery, with an
// artery in it) below the specimen, joined to both. Real cuts (cutting::cut_mesh) divide the fold
// and transect the specimen; grasps and ligatures are handed over as the stages hand them on.
#include <gtest/gtest.h>

#include <optional>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/clip.h"
#include "engine/kuhn_grid.h"
#include "engine/node_components.h"
#include "engine/sim_state.h"
#include "engine/topology_delta.h"
#include "metrics/procedure_errors.h"
#include "metrics/procedure_steps.h"

namespace serosa::metrics {
namespace {

constexpr int kSpecimen = 1, kMesentery = 2, kBase = 3, kArtery = 4;

SimState anatomy() {
  KuhnGridSpec spec;
  spec.xs = kuhn_axis(12, 0.005);        // x in [0, 6 cm]
  spec.ys = kuhn_axis(5, 0.005, -0.02);  // y in [-2 cm, 5 mm]
  spec.zs = kuhn_axis(1, 0.005);         // 5 mm thick
  spec.group = [](int i, int j, int) -> std::uint16_t {
    if (i < 2) return kBase;
    if (j == 4) return kSpecimen;
    return j == 1 ? kArtery : kMesentery;
  };
  SimState s;
  s.mesh = kuhn_grid(spec);
  s.tools.resize(3);
  s.shared.grasped.resize(3);
  return s;
}

ProcedureSteps steps() {
  return ProcedureSteps({kSpecimen, kBase, {kMesentery, kArtery}}, {"scope", "grasper", "loop"});
}

// Cuts the block by the rectangle x = x0 over y in [y0, y1], z across, as tool 1 would.
void cut(SimState& s, double x0, double y0, double y1) {
  const cutting::ConvexPolygon blade(
      {Vec3(x0, y0, -0.001), Vec3(x0, y1, -0.001), Vec3(x0, y1, 0.006), Vec3(x0, y0, 0.006)});
  CutEvent e;
  e.tool = 1;
  e.polygon_m = blade.points();
  e.delta = cutting::cut_mesh(s.mesh, blade).delta;
  apply(s.mesh, e.delta);
  s.events.cuts = {e};
}

std::vector<std::int32_t> nodes_where(const SimState& s, double x_min, double y_min) {
  std::vector<std::int32_t> out;
  for (std::int32_t v = 0; v < s.mesh.num_nodes(); ++v)
    if (s.mesh.rest[static_cast<std::size_t>(v)].x() >= x_min &&
        s.mesh.rest[static_cast<std::size_t>(v)].y() >= y_min)
      out.push_back(v);
  return out;
}

// A loop cinched round the specimen at rest x = x0.
Clip loop_at(const SimState& s, double x0) {
  Clip c;
  c.kind = Clip::Kind::kLoop;
  c.tool = 2;
  c.groups = {kSpecimen};
  c.rest_centre_m = Vec3(x0, 0.0025, 0.0025);
  for (std::int32_t v = 0; v < s.mesh.num_nodes(); ++v)
    if ((s.mesh.rest[static_cast<std::size_t>(v)] - Vec3(x0, 0.005, 0.0)).norm() < 1e-9) c.node = v;
  return c;
}

void lift(SimState& s, const std::vector<std::int32_t>& nodes, double dy) {
  for (std::int32_t v : nodes) s.mesh.x[static_cast<std::size_t>(v)].y() += dy;
}

TEST(ProcedureSteps, FollowTheFiveStepsInTheirOrder) {
  SimState s = anatomy();
  ProcedureSteps p = steps();
  ProcedureErrors errors(kArtery, {});
  double t = 0.0;
  const auto step = [&] {
    t += 0.1;
    p.step(t, s, errors);
    s.events.cuts.clear();
  };
  step();
  for (const ProcedureStep& st : p.steps()) EXPECT_FALSE(st.done) << st.name;

  // Expose: the grasper holds the specimen's far end and lifts it 5 mm, then 12 mm.
  s.shared.grasped[1] = nodes_where(s, 0.05, 0.005);
  ASSERT_FALSE(s.shared.grasped[1].empty());
  lift(s, s.shared.grasped[1], 0.005);
  step();
  EXPECT_FALSE(p.steps()[0].done);
  lift(s, s.shared.grasped[1], 0.007);
  step();
  EXPECT_TRUE(p.steps()[0].done);
  EXPECT_EQ(p.steps()[0].tool, 1);
  lift(s, s.shared.grasped[1], -0.012);

  // Divide the fold: a cut that stops short of the specimen leaves it joined ...
  cut(s, 0.0185, -0.021, -0.006);
  step();
  EXPECT_FALSE(p.steps()[1].done);
  // ... one up into the specimen's underside divides it down to the base's zone.
  cut(s, 0.0165, -0.021, 0.001);
  step();
  EXPECT_TRUE(p.steps()[1].done);

  // Secure the base: a loop far out on the specimen does not; one at its base does.
  s.shared.clips = {loop_at(s, 0.04)};
  step();
  EXPECT_FALSE(p.steps()[2].done);
  s.shared.clips = {loop_at(s, 0.015)};
  step();
  ASSERT_TRUE(p.steps()[2].done);
  EXPECT_EQ(p.steps()[2].tool, 2);

  // Transect beyond the loop: the far end is freed with 3/4 of the specimen's volume.
  cut(s, 0.0225, -0.021, 0.006);
  step();
  ASSERT_TRUE(p.steps()[3].done);
  EXPECT_NEAR(p.specimen_fraction(), 0.75, 1e-6);
  EXPECT_EQ(errors.count(ProcedureError::Kind::kTransectionAboveSecuring), 0);

  // Extract: the grasper carries the freed piece 4 cm away.
  EXPECT_FALSE(p.steps()[4].done);
  const std::vector<std::int32_t> piece = node_components(s.mesh);
  std::vector<std::int32_t> freed;
  const std::int32_t far = piece[static_cast<std::size_t>(nodes_where(s, 0.06, 0.005).front())];
  for (std::int32_t v = 0; v < s.mesh.num_nodes(); ++v)
    if (piece[static_cast<std::size_t>(v)] == far) freed.push_back(v);
  lift(s, freed, 0.03);
  step();
  EXPECT_FALSE(p.steps()[4].done);
  lift(s, freed, 0.015);
  step();
  EXPECT_TRUE(p.steps()[4].done);
  EXPECT_EQ(p.steps()[4].tool, 1);
  EXPECT_TRUE(p.completed());
  EXPECT_EQ(errors.count(ProcedureError::Kind::kSpecimenDropped), 0);

  nlohmann::json j;
  p.report(j);
  EXPECT_EQ(j["procedure"]["completed"], true);
  EXPECT_EQ(j["procedure"]["steps"][3]["name"], "transect");
  EXPECT_EQ(j["procedure"]["steps"][2]["tool"], "loop");
}

TEST(ProcedureSteps, ATransectionWithTheLoopOnTheSpecimenIsAboveTheSecuring) {
  SimState s = anatomy();
  ProcedureSteps p = steps();
  ProcedureErrors errors(kArtery, {});
  s.shared.grasped[1] = nodes_where(s, 0.05, 0.005);
  s.shared.clips = {loop_at(s, 0.04)};
  cut(s, 0.0225, -0.021, 0.006);
  p.step(0.1, s, errors);
  EXPECT_TRUE(p.steps()[3].done);
  EXPECT_FALSE(p.steps()[2].done);
  EXPECT_EQ(errors.count(ProcedureError::Kind::kTransectionAboveSecuring), 1);
  EXPECT_EQ(errors.count(ProcedureError::Kind::kSpecimenDropped), 0);
  EXPECT_FALSE(p.completed());
}

TEST(ProcedureSteps, AFreedSpecimenNoGrasperHoldsIsDroppedOnce) {
  SimState s = anatomy();
  ProcedureSteps p = steps();
  ProcedureErrors errors(kArtery, {});
  s.shared.clips = {loop_at(s, 0.015)};
  cut(s, 0.0225, -0.021, 0.006);
  p.step(0.1, s, errors);
  s.events.cuts.clear();
  p.step(0.2, s, errors);
  EXPECT_EQ(errors.count(ProcedureError::Kind::kSpecimenDropped), 1);
  nlohmann::json j;
  errors.report(j, true);
  EXPECT_EQ(j["specimens_dropped"], 1);
  EXPECT_EQ(j["errors"][0]["kind"], "specimen_dropped");
}

TEST(ProcedureSteps, ACutThatLeavesTheSpecimenJoinedTransectsNothing) {
  SimState s = anatomy();
  ProcedureSteps p = steps();
  ProcedureErrors errors(kArtery, {});
  cut(s, 0.0225, -0.01, 0.006);  // the fold's lower half still joins the far end to the base
  p.step(0.1, s, errors);
  EXPECT_FALSE(p.steps()[3].done);
  EXPECT_EQ(p.specimen_fraction(), 0.0);
}

}  // namespace
}  // namespace serosa::metrics
