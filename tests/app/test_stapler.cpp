// The linear cutter-stapler (engine/stapler.h) on the cantilever beam, through the whole pipeline
// (clips stage, FEM, cutting stage): closing its jaws across the beam fires it once: two staple
// lines clamp the tissue either side of the knife and the knife divides the beam between them,
// the mesh welded and its rest volume conserved; the lines hold under traction, carried by the
// piece each is on; fired on nothing it lays and cuts nothing; fired across a clip it is refused
// and cuts nothing, while the same fire beside the clip divides; a snapshot taken with the lines
// in place continues bit for bit; without "clips" the scene is an error at the tool's kind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "app_test_util.h"
#include "beam_scene.h"
#include "engine/clip.h"
#include "engine/input_error.h"
#include "engine/mesh_check.h"
#include "engine/node_components.h"
#include "engine/sim_state.h"
#include "engine/stapler.h"

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

const std::string kEffects = "\"fem\", \"surface\", \"contact\", \"clips\", \"cutting\"";

// The stapler over the beam with its knife at x (m), pointing down, jaws opening across the beam
// (+-z), the pin along the beam: the beam's axis 25 mm beyond the hinge. Open 0.6 rad by
// t0 + 0.05, closed (fired) at t0 + 0.10, held closed until 2 s.
std::string stapler_rows(double x, double t0 = 0.0, double y_tip = 0.010) {
  const std::string at = std::to_string(x) + "," + std::to_string(y_tip) + ",0," + kBeamAcross;
  const auto t = [&](double dt) { return std::to_string(t0 + dt) + ",stapler,"; };
  return t(0.0) + at + ",0.6\n" + t(0.05) + at + ",0.6\n" + t(0.10) + at + ",0.0\n" + t(2.0) + at +
         ",0.0\n";
}

std::unique_ptr<BeamRun> beam(const fs::path& dir, const std::string& rows,
                              const std::string& extra_tools = "",
                              const std::string& effects = kEffects) {
  return beam_scene(dir, "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n" + rows, effects,
                    scripted_tool("stapler", "stapler") + extra_tools);
}

double rest_volume(const TetMesh& m) {
  double v = 0.0;
  for (std::int32_t t = 0; t < m.num_tets(); ++t) v += m.rest_volume(t);
  return v;
}

std::int32_t pieces(const TetMesh& m) {
  const std::vector<std::int32_t> c = node_components(m);
  return c.empty() ? 0 : *std::max_element(c.begin(), c.end()) + 1;
}

TEST(Stapler, ClosedAcrossTheBeamItLaysTwoLinesAndDividesBetweenThem) {
  const fs::path dir = out_dir("stapler_fires");
  auto run = beam(dir, stapler_rows(0.0725));
  SimState& s = run->assembled.state;
  const double volume0 = rest_volume(s.mesh);
  const std::int32_t nodes0 = s.mesh.num_nodes();
  ASSERT_EQ(pieces(s.mesh), 1);
  // Step to the fire: the step whose cut is in the hand-off.
  for (int k = 0; k < 40 && s.events.cuts.empty(); ++k) run->comp.runner->step(s);
  ASSERT_EQ(s.events.cuts.size(), 1u);
  EXPECT_NEAR(s.time_s, 0.10, 0.006);
  ASSERT_EQ(s.shared.clips.size(), 2u);
  const StaplerJaws jaws = stapler_jaws(s.tools[0], 0.6);
  for (const Clip& c : s.shared.clips) {
    EXPECT_EQ(c.kind, Clip::Kind::kStaple);
    EXPECT_EQ(c.placed_s, s.shared.clips[0].placed_s);
    EXPECT_EQ(c.nodes, 9u);  // the beam's 3 x 3 nodes at x = 70 (75) mm
  }
  // The cut lies between the lines: every node it made, in the jaws' frame, inside the knife's
  // strip, nearer the knife than either line's band.
  const CutEvent& cut = s.events.cuts[0];
  EXPECT_EQ(cut.tool, 0u);
  ASSERT_FALSE(cut.delta.added_nodes.empty());
  for (std::int32_t n = nodes0; n < s.mesh.num_nodes(); ++n) {
    const Vec3 l = stapler_local(jaws, s.mesh.x[static_cast<std::size_t>(n)]);
    EXPECT_LT(std::abs(l.y()), kStapleLineOffset - kStapleLineHalfWidth) << "node " << n;
    EXPECT_TRUE(in_stapled_wedge(jaws, l)) << "node " << n;
  }
  // Divided in two, one line on each piece; welded, every tet positive, volume conserved.
  const std::vector<std::int32_t> comp = node_components(s.mesh);
  EXPECT_EQ(pieces(s.mesh), 2);
  EXPECT_NE(comp[static_cast<std::size_t>(s.shared.clips[0].node)],
            comp[static_cast<std::size_t>(s.shared.clips[1].node)]);
  const MeshCheckReport check = check_mesh(s.mesh);
  EXPECT_TRUE(check.valid) << (check.problems.empty() ? "" : check.problems[0]);
  EXPECT_EQ(check.overshared_faces, 0);
  EXPECT_EQ(check.misoriented_faces, 0);
  EXPECT_NEAR(rest_volume(s.mesh), volume0, 1e-12 * volume0);
  // Once per closure: held closed, it fires no more.
  run->comp.runner->run(s, 60);
  const CuttingStageStats& st = run->comp.cutting->stats();
  EXPECT_EQ(st.stapler_fires, 1u);
  EXPECT_EQ(st.stapler_fires_held, 0u);
  EXPECT_EQ(st.cuts, 1u);
  EXPECT_EQ(s.shared.clips.size(), 2u);
  EXPECT_EQ(pieces(s.mesh), 2);
}

TEST(Stapler, ItsLinesHoldUnderTractionCarriedByTheirPieces) {
  // Fired at 7.25 cm (t = 0.1 s; the lines settle by 0.4 s); the grasper holds the beam's end at
  // 9.5 cm from 0.05 s and lifts it 1 cm between 0.5 and 0.7 s: it pulls the distal piece.
  const std::string g = "grasper,0.095,";
  const std::string rows = stapler_rows(0.0725) + "0.00," + g + "0.002,0," + kBeamDown +
                           ",0.9\n0.02," + g + "0.002,0," + kBeamDown + ",0.9\n0.05," + g +
                           "0.002,0," + kBeamDown + ",0.0\n0.50," + g + "0.002,0," + kBeamDown +
                           ",0.0\n0.70," + g + "0.012,0," + kBeamDown + ",0.0\n1.20," + g +
                           "0.012,0," + kBeamDown + ",0.0\n";
  const fs::path dir = out_dir("stapler_traction");
  auto run = beam(dir, rows, scripted_tool("grasper", "grasper"));
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 90);  // t = 0.45: fired, pressed and settled
  ASSERT_EQ(s.shared.clips.size(), 2u);
  // Each line's clamped nodes: those pressed to its plane at its place.
  std::array<std::vector<std::int32_t>, 2> clamped;
  std::array<std::vector<double>, 2> gaps;  // pairwise distances within each line, m
  const auto in_line = [&](const Clip& c, const Vec3& p) {
    return c.frame.transpose() * (p - c.hinge_m);
  };
  for (std::size_t k = 0; k < 2; ++k) {
    const Clip& c = s.shared.clips[k];
    for (std::int32_t n = 0; n < s.mesh.num_nodes(); ++n) {
      const Vec3 l = in_line(c, s.mesh.x[static_cast<std::size_t>(n)]);
      if (l.z() >= kStapleStart && l.z() <= kCartridgeLength &&
          std::abs(l.y()) <= kStapleLineHalfWidth && std::abs(l.x()) <= 0.5 * kStapleGap + 1e-12)
        clamped[k].push_back(n);
    }
    ASSERT_EQ(clamped[k].size(), c.nodes);
    for (std::int32_t a : clamped[k])
      for (std::int32_t b : clamped[k])
        gaps[k].push_back(
            (s.mesh.x[static_cast<std::size_t>(a)] - s.mesh.x[static_cast<std::size_t>(b)]).norm());
  }
  const Vec3 distal0 = 0.5 * (s.shared.clips[0].end(0) + s.shared.clips[0].end(1));
  const Vec3 proximal0 = 0.5 * (s.shared.clips[1].end(0) + s.shared.clips[1].end(1));
  run->comp.runner->run(s, 100);  // t = 0.95: lifted and held
  ASSERT_EQ(s.shared.clips.size(), 2u);
  // The lines still hold what they clamped, together, pressed, in their frames as they are now.
  for (std::size_t k = 0; k < 2; ++k) {
    const Clip& c = s.shared.clips[k];
    std::size_t i = 0;
    for (std::int32_t a : clamped[k]) {
      EXPECT_EQ(s.mesh.fixed[static_cast<std::size_t>(a)], 1);
      const Vec3 l = in_line(c, s.mesh.x[static_cast<std::size_t>(a)]);
      EXPECT_LE(std::abs(l.x()), 0.5 * kStapleGap + 1e-9);
      for (std::int32_t b : clamped[k])
        EXPECT_NEAR(
            (s.mesh.x[static_cast<std::size_t>(a)] - s.mesh.x[static_cast<std::size_t>(b)]).norm(),
            gaps[k][i++], 1e-9);
    }
    EXPECT_NEAR(c.frame.determinant(), 1.0, 1e-9);
  }
  // The pulled piece carried its line up; the one on the fixed side stayed.
  const Vec3 distal = 0.5 * (s.shared.clips[0].end(0) + s.shared.clips[0].end(1)) - distal0;
  const Vec3 proximal = 0.5 * (s.shared.clips[1].end(0) + s.shared.clips[1].end(1)) - proximal0;
  EXPECT_GT(distal.y(), 0.002) << distal.transpose();
  EXPECT_LT(proximal.norm(), 0.5 * distal.norm()) << proximal.transpose();
  for (const Vec3& x : s.mesh.x) ASSERT_TRUE(x.allFinite());
}

TEST(Stapler, FiredOnNothingItLaysAndCutsNothing) {
  const fs::path dir = out_dir("stapler_nothing");
  auto run = beam(dir, stapler_rows(0.0725, 0.0, 0.060));  // its jaws 2 cm above the beam
  SimState& s = run->assembled.state;
  const std::vector<std::uint8_t> fixed0 = s.mesh.fixed;
  const std::int32_t tets0 = s.mesh.num_tets();
  run->comp.runner->run(s, 40);
  EXPECT_TRUE(s.shared.clips.empty());
  EXPECT_EQ(contact::clips_dropped(run->assembled.state, 0), 1);
  EXPECT_EQ(contact::stapler_refused(run->assembled.state, 0), 0);
  const CuttingStageStats& st = run->comp.cutting->stats();
  EXPECT_EQ(st.stapler_fires, 0u);
  EXPECT_EQ(st.stapler_fires_held, 1u);
  EXPECT_EQ(st.cuts, 0u);
  EXPECT_EQ(s.mesh.num_tets(), tets0);
  EXPECT_EQ(s.mesh.fixed, fixed0);
}

TEST(Stapler, FiredAcrossAClipItIsRefusedAndBesideItDivides) {
  // A clip at 7 cm (closed by 0.1 s); the stapler fires across it at 7.1 cm (0.3 s), then beside
  // it at 3.25 cm (0.6 s).
  const std::string at = "0.070000,-0.004,0," + kBeamAcross;
  const std::string clip = "0.00,clipper," + at + ",0.7\n0.05,clipper," + at +
                           ",0.7\n0.10,clipper," + at + ",0.0\n2.00,clipper," + at + ",0.0\n";
  const auto row = [&](double t, double x, double jaw) {
    return std::to_string(t) + ",stapler," + std::to_string(x) + ",0.010,0," + kBeamAcross + "," +
           std::to_string(jaw) + "\n";
  };
  const std::string rows = clip + row(0.0, 0.071, 0.0) + row(0.2, 0.071, 0.6) +
                           row(0.25, 0.071, 0.6) + row(0.3, 0.071, 0.0) + row(0.35, 0.071, 0.0) +
                           row(0.4, 0.0325, 0.0) + row(0.45, 0.0325, 0.6) + row(0.5, 0.0325, 0.6) +
                           row(0.55, 0.0325, 0.0) + row(2.0, 0.0325, 0.0);
  const fs::path dir = out_dir("stapler_on_clip");
  auto run = beam(dir, rows, scripted_tool("clipper", "clip-applier"));
  SimState& s = run->assembled.state;
  const std::int32_t tets0 = s.mesh.num_tets();
  run->comp.runner->run(s, 70);  // t = 0.35: fired on the clip
  ASSERT_EQ(s.shared.clips.size(), 1u);
  EXPECT_EQ(s.shared.clips[0].kind, Clip::Kind::kClip);
  EXPECT_EQ(contact::stapler_refused(run->assembled.state, 0), 1);
  const CuttingStageStats& st = run->comp.cutting->stats();
  EXPECT_EQ(st.stapler_fires_held, 1u);
  EXPECT_EQ(st.cuts, 0u);
  EXPECT_EQ(s.mesh.num_tets(), tets0);
  run->comp.runner->run(s, 50);  // t = 0.6: fired beside it
  EXPECT_EQ(contact::stapler_refused(run->assembled.state, 0), 1);
  EXPECT_EQ(st.stapler_fires, 1u);
  EXPECT_EQ(st.cuts, 1u);
  EXPECT_EQ(s.shared.clips.size(), 3u);
  EXPECT_EQ(pieces(s.mesh), 2);
}

TEST(Stapler, ARestoredSnapshotWithItsLinesContinuesBitForBit) {
  const fs::path dir = out_dir("stapler_snapshot");
  auto run = beam(dir, stapler_rows(0.0725));
  SimState& s = run->assembled.state;
  run->comp.runner->run(s, 40);  // fired at 0.1 s, pressing
  ASSERT_EQ(s.shared.clips.size(), 2u);
  const std::vector<std::uint8_t> bytes = run->comp.runner->snapshot(s);
  auto other = restored(*run, bytes, "stapler snapshot");
  SimState& o = other->assembled.state;
  ASSERT_EQ(o.shared.clips.size(), 2u);
  for (int k = 0; k < 50; ++k) {  // through the settling and on
    run->comp.runner->step(s);
    other->comp.runner->step(o);
    ASSERT_EQ(state_hash(o), state_hash(s)) << "step " << s.step;
  }
  EXPECT_EQ(other->comp.runner->snapshot(o), run->comp.runner->snapshot(s));
}

TEST(Stapler, WithoutTheClipsEffectTheSceneIsAnErrorAtTheToolsKind) {
  const fs::path dir = out_dir("stapler_no_clips");
  try {
    (void)beam(dir, stapler_rows(0.0725), "", "\"fem\", \"surface\", \"contact\", \"cutting\"");
    FAIL() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tool[0].kind"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("\"clips\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace serosa::app
