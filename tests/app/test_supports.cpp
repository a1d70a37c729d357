// The supports (contact/support_stage.h): with gravity on, a cantilever beam sags; a support
// plane under it holds it up, and it comes to rest on the plane instead of bouncing. The plane
// pushes only along its normal and only on nodes below it. Bad input: a [[support]] without the
// effect, the effect without a [[support]], a zero normal, an abdomen drawn without a support.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "app_test_util.h"
#include "beam_scene.h"
#include "contact/support_stage.h"
#include "engine/input_error.h"
#include "engine/sim_state.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

const std::string kCsv = "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n0,g,0.5,0.5,0.5,1,0,0,0,0\n";
const std::string kTool = scripted_tool("g", "grasper");
// Just under the beam (its underside is y = -5 mm).
const std::string kFloor =
    "[[support]]\nname = \"floor\"\npoint = [0, -0.0052, 0]\nnormal = [0, 2, 0]\n";

double lowest_y(const SimState& s) {
  double y = std::numeric_limits<double>::infinity();
  for (const Vec3& x : s.mesh.x) y = std::min(y, x.y());
  return y;
}

TEST(Supports, HoldTheSaggingBeamUpAndItComesToRestOnThem) {
  auto free = beam_scene(out_dir("support_none"), kCsv, "\"fem\", \"gravity\"", kTool);
  SimState& f = free->assembled.state;
  free->comp.runner->run(f, 200);
  EXPECT_LT(lowest_y(f), -0.0052 - 0.005);  // without it the tip sags more than 5 mm below

  auto run = beam_scene(out_dir("support_floor"), kCsv, "\"fem\", \"gravity\", \"supports\"", kTool,
                        kFloor);
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 400);           // 2 s
  EXPECT_GT(lowest_y(s), -0.0052 - 2e-3);  // the penalty's sinking under the beam's weight
  double vmax = 0.0;
  for (const Vec3& v : s.mesh.v) vmax = std::max(vmax, v.norm());
  EXPECT_LT(vmax, 1e-3);  // at rest, not bouncing
  EXPECT_EQ(run->scene.supports.size(), 1u);
  EXPECT_NEAR(run->scene.supports[0].normal.y(), 1.0, 1e-15);  // normalised
}

TEST(Supports, PushOnlyAlongTheNormalOnNodesBelowThePlane) {
  auto run =
      beam_scene(out_dir("support_push"), kCsv, "\"fem\", \"supports\"", kTool,
                 "[[support]]\nname = \"slope\"\npoint = [0.05, 0, 0]\nnormal = [1, 1, 0]\n");
  SimState s = run->assembled.state;
  for (double& m : s.mesh.mass) m = 1e-3;
  contact::SupportStage stage(run->scene, true);
  stage.step({0, 0.0, 0.005}, s);
  const Vec3 n = Vec3(1, 1, 0).normalized();
  std::int64_t below = 0;
  for (std::size_t i = 0; i < s.mesh.x.size(); ++i) {
    const double d = (s.mesh.x[i] - Vec3(0.05, 0, 0)).dot(n);
    const Vec3 f = s.events.external_force_n.empty() ? Vec3::Zero() : s.events.external_force_n[i];
    if (d >= 0.0 || s.mesh.fixed[i] != 0) {
      EXPECT_EQ(f.norm(), 0.0) << "node " << i;
      continue;
    }
    ++below;
    EXPECT_LT((f - f.dot(n) * n).norm(), 1e-12 * f.norm()) << "node " << i;
    EXPECT_NEAR(f.dot(n),
                -d * std::min(contact::kSupportStiffness, contact::kSupportBeta * 1e-3 / 2.5e-5),
                1e-12);
  }
  EXPECT_GT(below, 0);
  EXPECT_EQ(stage.contacts(), below);
}

void expect_error(const std::string& effects, const std::string& extra, const std::string& key) {
  try {
    (void)beam_scene(out_dir("support_bad"), kCsv, effects, kTool, extra);
    FAIL() << "loaded: " << key;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
  }
}

TEST(Supports, BadInputIsAnErrorNamingTheKey) {
  expect_error("\"fem\", \"gravity\"", kFloor, "support");
  expect_error("\"fem\", \"supports\"", "", "scene.effects");
  expect_error("\"fem\", \"supports\"",
               "[[support]]\nname = \"x\"\npoint = [0, 0, 0]\nnormal = [0, 0, 0]\n",
               "support[0].normal");
  expect_error("\"fem\", \"supports\"", kFloor + kFloor, "support[1].name");
  expect_error("\"fem\"", "[render]\nsurroundings = \"abdomen\"\n", "render.surroundings");
  expect_error("\"fem\"", "[render]\nsurroundings = \"jungle\"\n", "render.surroundings");
}

}  // namespace
}  // namespace serosa::app
