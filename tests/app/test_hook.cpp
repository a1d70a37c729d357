// The hook cautery (tool kind "hook", effect "cautery"; cutting/cutting_stage.h) on a cantilever
// beam: drawn down through the tissue with its pedal held, it divides the tissue its crook
// passed through when the pedal comes up and coagulates the band around its path; the same path
// with the pedal up, or the pedal held while the hook stands still, divides nothing; the
// coagulated band is drawn; a restored snapshot mid-stroke continues bit for bit.
#include <gtest/gtest.h>

#include <fstream>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/render_frame_from_surface.h"
#include "app_test_util.h"
#include "beam_scene.h"
#include "engine/hook.h"
#include "engine/sim_state.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

const std::string kAcross = kBeamAcross;

std::unique_ptr<BeamRun> beam(const fs::path& dir, const std::string& csv) {
  return beam_scene(dir, "t,tool,px,py,pz,qw,qx,qy,qz,jaw,buttons\n" + csv,
                    "\"fem\", \"surface\", \"cautery\"", scripted_tool("hook", "hook"));
}

// The hook comes down to 1 mm above the beam at x = 5 cm (crook z in [-1.5, 1.5] mm), then is
// drawn 10 mm down into it between 0.06 and 0.16 s with the pedal as given, and lifts it at
// 0.17 s; standing still, it holds the pedal at y = 0 (a row of nodes) instead.
std::string path(int pedal_down, bool moving = true) {
  const auto row = [](const std::string& t, double y, int buttons) {
    return t + ",hook,0.05," + std::to_string(y) + ",-0.0015," + kAcross + ",0," +
           std::to_string(buttons) + "\n";
  };
  const double from = moving ? 0.006 : 0.0, to = moving ? -0.004 : 0.0;
  return row("0.00", 0.012, 0) + row("0.05", from, 0) + row("0.06", from, pedal_down) +
         row("0.16", to, pedal_down) + row("0.17", to, 0) + row("1.00", to, 0);
}

// Distance from p to the rectangle the crook swept: x = 5 cm, y in [-4, 6] mm, z in [-1.5, 1.5].
double to_swept(const Vec3& p) {
  const Vec3 q(0.05, std::clamp(p.y(), -0.004, 0.006), std::clamp(p.z(), -0.0015, 0.0015));
  return (p - q).norm();
}

TEST(Hook, DividesWhatItsLiveCrookPassedThroughAndCoagulatesAroundIt) {
  const fs::path dir = out_dir("hook_live");
  auto run = beam(dir, path(static_cast<int>(kPedalButton)));
  SimState& s = run->assembled.state;
  const std::int32_t tets0 = s.mesh.num_tets();
  run->comp.runner->run(s, 50);  // t = 0.25: released at 0.17
  const CuttingStageStats& st = run->comp.cutting->stats();
  EXPECT_EQ(st.hook_strokes, 1u);
  EXPECT_GE(st.cuts, 1u);
  EXPECT_GT(s.mesh.num_tets(), tets0);
  ASSERT_EQ(st.stroke_reports.size(), 1u);
  EXPECT_GT(st.stroke_reports[0].crack_area_m2, 0.0);
  EXPECT_EQ(st.stroke_reports[0].pinned, 0);
  // The coagulated band: every marked node near the path (or made by the hook's cut on it).
  ASSERT_EQ(s.blocks.cutting.coagulated.size(), static_cast<std::size_t>(s.mesh.num_nodes()));
  std::size_t marked = 0;
  for (std::size_t n = 0; n < s.blocks.cutting.coagulated.size(); ++n) {
    const double d = to_swept(s.mesh.rest[n]);
    if (s.blocks.cutting.coagulated[n] != 0) {
      ++marked;
      EXPECT_LE(d, kCoagulationRadius + 1e-3) << "node " << n;
    }
  }
  EXPECT_GT(marked, 4u);
  // Drawn: faces with three coagulated nodes take the coagulated material (the hook's own
  // wound is dry: its faces' nodes are all coagulated).
  render::RenderFrame frame;
  fill_render_frame(s.mesh, s.shared.surface, {}, false, frame, &s.blocks.cutting.coagulated,
                    s.blocks.cutting.coagulated_version);
  EXPECT_EQ(frame.material_version, s.blocks.cutting.coagulated_version);
  EXPECT_GT(s.blocks.cutting.coagulated_version, 0u);
  std::size_t charred = 0;
  for (std::size_t i = 0; i < frame.tri_cut.size(); ++i) {
    if (frame.tri_cut[i] != 2) continue;
    ++charred;
    for (std::int32_t n : s.shared.surface.faces[i])
      EXPECT_EQ(s.blocks.cutting.coagulated[static_cast<std::size_t>(n)], 1);
  }
  EXPECT_GT(charred, 0u);
}

TEST(Hook, WithoutThePedalOrWithoutMovingItDividesNothing) {
  for (const auto& [name, csv, marks] :
       {std::tuple{"hook_off", path(0), false},
        std::tuple{"hook_still", path(static_cast<int>(kPedalButton), false), true}}) {
    SCOPED_TRACE(name);
    auto run = beam(out_dir(name), csv);
    SimState& s = run->assembled.state;
    const std::int32_t tets0 = s.mesh.num_tets();
    run->comp.runner->run(s, 50);
    EXPECT_EQ(run->comp.cutting->stats().cuts, 0u);
    EXPECT_EQ(s.mesh.num_tets(), tets0);
    EXPECT_EQ(run->comp.cutting->stats().coagulated_nodes > 0, marks);
  }
}

TEST(Hook, ARestoredSnapshotMidStrokeContinuesBitForBit) {
  const fs::path dir = out_dir("hook_snapshot");
  auto run = beam(dir, path(static_cast<int>(kPedalButton)));
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 25);  // pedal down, the stroke half drawn
  const std::vector<std::uint8_t> bytes = run->comp.runner->snapshot(s);
  auto other = restored(*run, bytes, "hook snapshot");
  SimState& o = other->assembled.state;
  EXPECT_EQ(o.blocks.cutting.coagulated, s.blocks.cutting.coagulated);
  for (int k = 0; k < 30; ++k) {  // through the release and the cut
    run->comp.runner->step(s);
    other->comp.runner->step(o);
    ASSERT_EQ(state_hash(o), state_hash(s)) << "step " << s.step;
  }
  EXPECT_EQ(other->comp.runner->snapshot(o), run->comp.runner->snapshot(s));
  EXPECT_EQ(other->comp.cutting->stats().hook_strokes, 1u);
}

}  // namespace
}  // namespace serosa::app
