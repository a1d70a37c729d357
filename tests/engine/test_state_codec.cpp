// The whole-state encoding (engine/state_codec.h): a SimState read back equals the one written,
// field for field and byte for byte; a snapshot cut short or damaged anywhere is an InputError
// naming it, never a crash or a read past its end.
#include <gtest/gtest.h>

#include <random>

#include "engine/input_error.h"
#include "engine/runner.h"
#include "engine/state_codec.h"
#include "support/test_meshes.h"

namespace serosa {
namespace {

SimState random_state(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SimState s;
  s.mesh = test_meshes::kuhn_box(3, 2, 2, 2);
  s.mesh.fill_node_state();
  for (Vec3& x : s.mesh.x) x += 1e-3 * Vec3(u(rng), u(rng), u(rng));
  for (Vec3& v : s.mesh.v) v = Vec3(u(rng), u(rng), u(rng));
  for (double& m : s.mesh.mass) m = 1.0 + u(rng);
  s.mesh.fixed[static_cast<std::size_t>(seed) % s.mesh.fixed.size()] = 1;
  s.mesh.topology_version = seed;
  s.step = seed * 7u;
  s.time_s = 0.005 * static_cast<double>(s.step);
  s.tools.resize(seed % 4);
  for (ToolState& t : s.tools) {
    t.tick = rng();
    t.tip_m = {u(rng), u(rng), u(rng)};
    t.jaw_rad = u(rng);
    t.buttons = rng() & 3u;
  }
  if (seed % 2 == 0) s.events.external_force_n.assign(s.mesh.x.size(), Vec3(u(rng), 0.0, 1.0));
  s.events.nodes_moved = seed % 3 == 0;
  s.events.tool_force_n.assign(s.tools.size(), Vec3(0.0, u(rng), 0.0));
  SurfaceMesh& f = s.shared.surface;
  for (std::int32_t i = 0; i + 2 < s.mesh.num_nodes(); i += 3) {
    f.faces.push_back({i, i + 1, i + 2});
    f.face_tet.push_back(i / 3);
    f.face_group.push_back(static_cast<std::uint16_t>(1 + i % 2));
    f.face_cut.push_back(static_cast<std::uint8_t>(i % 2));
  }
  f.groups.push_back({1, 0, f.num_faces()});
  f.topology_version = seed;
  return s;
}

std::vector<std::uint8_t> encode(const SimState& s) {
  StateWriter w;
  write_sim_state(w, s);
  return std::move(w.bytes());
}

TEST(StateCodec, ReadBackEqualsWhatWasWrittenForManyStates) {
  for (std::uint32_t seed = 1; seed <= 200; ++seed) {
    const SimState s = random_state(seed);
    const std::vector<std::uint8_t> bytes = encode(s);
    StateReader r(bytes, "state");
    const SimState back = read_sim_state(r);
    ASSERT_EQ(r.left(), 0u);
    EXPECT_EQ(state_hash(back), state_hash(s));
    EXPECT_EQ(back.mesh.rest, s.mesh.rest);
    EXPECT_EQ(back.mesh.mass, s.mesh.mass);
    EXPECT_EQ(back.mesh.fixed, s.mesh.fixed);
    EXPECT_EQ(back.events.nodes_moved, s.events.nodes_moved);
    EXPECT_EQ(back.shared.surface.faces, s.shared.surface.faces);
    EXPECT_EQ(back.shared.surface.groups.size(), s.shared.surface.groups.size());
    EXPECT_EQ(encode(back), bytes) << "seed " << seed;  // padding never reaches the bytes
  }
}

TEST(StateCodec, EveryTruncationAndManyFlipsAreInputErrors) {
  const std::vector<std::uint8_t> bytes = encode(random_state(4));
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::vector<std::uint8_t> cut(bytes.begin(),
                                        bytes.begin() + static_cast<std::ptrdiff_t>(n));
    StateReader r(cut, "cut.snapshot");
    EXPECT_THROW((void)read_sim_state(r), InputError) << n << " bytes";
  }
  std::mt19937 rng(3);
  for (int k = 0; k < 2000; ++k) {
    std::vector<std::uint8_t> bad = bytes;
    bad[std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(rng)] ^=
        static_cast<std::uint8_t>(1u << (k % 8));
    StateReader r(bad, "flipped.snapshot");
    try {
      (void)read_sim_state(r);  // a flipped value may still be a valid state
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("flipped.snapshot"), std::string::npos);
    }
  }
}

TEST(StateCodec, CutsInFlightAreNotSnapshotted) {
  SimState s = random_state(2);
  s.events.cuts.emplace_back();
  StateWriter w;
  EXPECT_THROW(write_sim_state(w, s), std::logic_error);
}

// Every block of the state, filled at random: a snapshot carries each in a section of its own,
// and what comes back writes the same bytes.
void random_blocks(std::uint32_t seed, SimState& s) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto n = static_cast<std::int32_t>(s.mesh.num_nodes());
  StageBlocks& b = s.blocks;
  b.contact.grasps.resize(s.tools.size());
  for (ContactBlock::Grasp& g : b.contact.grasps) {
    g.holding = rng() % 2 == 0;
    for (int k = 0; k < static_cast<int>(rng() % 4); ++k) {
      g.nodes.push_back(static_cast<std::int32_t>(rng() % static_cast<unsigned>(n)));
      g.local.emplace_back(u(rng), u(rng), u(rng));
      g.was_fixed.push_back(static_cast<std::uint8_t>(rng() % 2));
    }
    g.widest_rad = u(rng);
  }
  for (int k = 0; k < static_cast<int>(seed % 3); ++k) {
    ClipsBlock::Placed p;
    p.clip.kind = static_cast<Clip::Kind>(rng() % 3);
    p.clip.hinge_m = Vec3(u(rng), u(rng), u(rng));
    p.clip.groups = {1, 2};
    p.nodes = {0, n - 1};
    p.local = {Vec3(u(rng), 0.0, 0.0), Vec3(0.0, u(rng), 0.0)};
    p.settled = rng() % 2 == 0;
    b.clips.placed.push_back(p);
  }
  b.clips.widest_rad.assign(s.tools.size(), u(rng));
  b.clips.triggers.assign(s.tools.size(), StaplerTrigger{u(rng)});
  CuttingBlock::Follow f;
  f.before = s.tools.empty() ? std::nullopt : std::optional<ToolState>(s.tools[0]);
  StrokeRecord r;
  r.steps = seed;
  r.samples.resize(seed % 5);
  for (StrokeSample& x : r.samples) x.bary = {u(rng), u(rng), u(rng), u(rng)};
  if (seed % 2 == 1) f.stroke = r;
  b.cutting.scissors.assign(1 + seed % 2, f);
  b.cutting.coagulated.assign(static_cast<std::size_t>(n), static_cast<std::uint8_t>(seed % 2));
  b.bleeding.sources.resize(seed % 3);
  b.bleeding.stain.assign(static_cast<std::size_t>(n), static_cast<float>(u(rng)));
  b.smoke.puffs.resize(seed % 4);
  b.smoke.next = rng();
}

TEST(StateCodec, ASnapshotHoldsTheStateAndEveryBlockAndWritesTheSameBytesBack) {
  Runner runner(0.005);
  std::vector<std::string> names{"state"};
  const StageBlocks none;
  StageBlocks::each_named(none, [&](const char* name, const auto&) { names.push_back(name); });
  for (std::uint32_t seed = 1; seed < 200; ++seed) {
    SimState s = random_state(seed);
    random_blocks(seed, s);
    const std::vector<std::uint8_t> snap = runner.snapshot(s);
    const auto sections = snapshot_sections(snap, "snap");
    ASSERT_EQ(sections.size(), names.size());
    for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(sections[i].name, names[i]);
    SimState back;
    runner.restore(snap, back, "snap");
    ASSERT_EQ(state_hash(back), state_hash(s));
    ASSERT_EQ(runner.snapshot(back), snap) << "seed " << seed;
    std::vector<std::uint8_t> wrong = snap;
    wrong[0] = 'X';
    EXPECT_THROW(runner.restore(wrong, back, "snap"), InputError);
    // A block cut short anywhere is an error naming it, never a read past its end.
    const SnapshotSection& last = sections.back();
    std::vector<std::uint8_t> cut(
        snap.begin(), snap.begin() + static_cast<std::ptrdiff_t>(last.offset + last.size / 2));
    EXPECT_THROW(runner.restore(cut, back, "snap"), InputError);
  }
}

}  // namespace
}  // namespace serosa
