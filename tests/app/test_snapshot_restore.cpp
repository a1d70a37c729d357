// Whole-state snapshots (engine/state_codec.h, Runner::snapshot): a run restored from a snapshot
// taken at a random step continues bit for bit like the uninterrupted one, during a grasp and
// after the cut included; and `serosa replay --headless --verify --from T` starts from the
// recording's snapshot at or before T.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "app/assemble_state.h"
#include "app/assessment_report.h"
#include "app/compose.h"
#include "app/headless.h"
#include "app_test_util.h"
#include "engine/input_error.h"
#include "engine/sim_state.h"
#include "recording/recording_reader.h"
#include "recording/recording_writer.h"
#include "replay/replay.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

constexpr std::uint64_t kSteps = 1000;  // the default scene's 5 s procedure

struct Pipeline {
  AssembledScene assembled;
  Composition comp;
};

std::unique_ptr<Pipeline> build(const Scene& scene) {
  auto p = std::make_unique<Pipeline>();
  p->assembled = assemble_state(scene);
  p->comp = compose(scene, p->assembled);
  return p;
}

struct Taken {
  std::vector<std::uint8_t> bytes;
  bool holding = false;  // the grasper held tissue
  bool after_cut = false;
};

TEST(Snapshot, RestoreAtRandomStepsEqualsTheUninterruptedRunBitForBit) {
  const Scene scene = load_scene(source("config/transection.toml"));
  // Random steps from the grasp (1.8 s) to near the end, plus the first steps after the grasp
  // took hold and after the cut (the lagged factor patched for each).
  std::mt19937 rng(20261202);
  std::uniform_int_distribution<std::uint64_t> pick(340, kSteps - 40);
  std::set<std::uint64_t> wanted;
  while (wanted.size() < 5) wanted.insert(pick(rng));

  std::size_t grasper = 0;
  while (grasper < scene.tools.size() && scene.tools[grasper].kind != ToolKind::kGrasper) ++grasper;
  ASSERT_LT(grasper, scene.tools.size());

  auto run = build(scene);
  SimState& s = run->assembled.state;
  std::map<std::uint64_t, std::uint64_t> hashes;  // steps taken -> state hash
  std::map<std::uint64_t, Taken> taken;
  bool cut_seen = false;
  bool hold_seen = false;
  while (s.step < kSteps) {
    run->comp.runner->step(s);
    hashes[s.step] = state_hash(s);
    const bool cut_now = !s.events.cuts.empty();
    const bool first_after_cut = !cut_now && !cut_seen && run->comp.cutting->stats().cuts > 0;
    if (first_after_cut) cut_seen = true;
    // The step after the grasp took hold: the lagged factor is patched for the held nodes.
    const bool first_holding = !hold_seen && contact::grasped_counts(s)[grasper] > 0;
    if (first_holding) hold_seen = true;
    // A snapshot waits for a step with no cut in flight.
    const bool due = !wanted.empty() && s.step >= *wanted.begin();
    if (!cut_now && (first_after_cut || first_holding || due)) {
      wanted.erase(wanted.begin(), wanted.upper_bound(s.step));
      taken[s.step] = {run->comp.runner->snapshot(s), contact::grasped_counts(s)[grasper] > 0,
                       run->comp.cutting->stats().cuts > 0};
    }
  }
  const std::vector<std::uint8_t> final_bytes = run->comp.runner->snapshot(s);
  ASSERT_GE(taken.size(), 6u);
  ASSERT_TRUE(hold_seen);
  ASSERT_TRUE(cut_seen);
  const auto holding =
      std::count_if(taken.begin(), taken.end(), [](const auto& t) { return t.second.holding; });
  const auto after_cut =
      std::count_if(taken.begin(), taken.end(), [](const auto& t) { return t.second.after_cut; });
  EXPECT_GE(holding, 1);
  EXPECT_GE(after_cut, 1);

  // Each restored into a fresh pipeline: 40 steps on, every hash equal; the last one to the end,
  // where the whole state (every stage's block: metric sums too) equals the uninterrupted run's.
  for (auto it = taken.begin(); it != taken.end(); ++it) {
    SCOPED_TRACE("restored after step " + std::to_string(it->first));
    auto r = build(scene);
    SimState& rs = r->assembled.state;
    r->comp.runner->restore(it->second.bytes, rs, "snapshot");
    ASSERT_EQ(rs.step, it->first);
    EXPECT_EQ(state_hash(rs), hashes.at(it->first));
    // Restore, then save: the same bytes, part by part.
    const std::vector<std::uint8_t> again = r->comp.runner->snapshot(rs);
    const auto parts = snapshot_sections(again, "again"),
               want = snapshot_sections(it->second.bytes, "taken");
    ASSERT_EQ(parts.size(), want.size());
    for (std::size_t k = 0; k < parts.size(); ++k)
      EXPECT_TRUE(std::equal(
          again.begin() + static_cast<std::ptrdiff_t>(parts[k].offset),
          again.begin() + static_cast<std::ptrdiff_t>(parts[k].offset + parts[k].size),
          it->second.bytes.begin() + static_cast<std::ptrdiff_t>(want[k].offset),
          it->second.bytes.begin() + static_cast<std::ptrdiff_t>(want[k].offset + want[k].size)))
          << "the part " << parts[k].name;
    const bool last = std::next(it) == taken.end();
    const std::uint64_t until = last ? kSteps : std::min(kSteps, it->first + 40);
    while (rs.step < until) {
      r->comp.runner->step(rs);
      ASSERT_EQ(state_hash(rs), hashes.at(rs.step)) << "step " << rs.step;
    }
    if (last) {
      EXPECT_EQ(r->comp.runner->snapshot(rs), final_bytes);
    }
  }
}

// The default procedure, five steps with four exchanges of the right hand: snapshots at random
// steps and at the first step after each exchange (the hands' account is in the metrics' block),
// each restored into a fresh pipeline; 60 steps on, every hash equals the uninterrupted run's, and
// the last one, run to the end, gives the same whole state, byte for byte. The final state alone,
// adopted by a fresh pipeline, gives the run's report.
TEST(Snapshot, TheDefaultProcedureWithItsExchangesRestoresBitForBitAtRandomSteps) {
  const Scene scene = load_scene(source("config/appendectomy.toml"));
  const auto steps = static_cast<std::uint64_t>(scene.headless.steps);
  std::mt19937 rng(20261207);
  std::uniform_int_distribution<std::uint64_t> pick(1, steps - 61);
  std::set<std::uint64_t> wanted;
  while (wanted.size() < 4) wanted.insert(pick(rng));

  auto run = build(scene);
  SimState& s = run->assembled.state;
  run->comp.runner->prepare(s);
  std::map<std::uint64_t, std::uint64_t> hashes;
  std::map<std::uint64_t, std::vector<std::uint8_t>> taken;
  std::size_t exchanges_seen = 0;
  bool exchange_pending = false;
  while (s.step < steps) {
    run->comp.runner->step(s);
    hashes[s.step] = state_hash(s);
    const std::size_t exchanges = s.blocks.metrics.exchanges.exchanges.size();
    exchange_pending = exchange_pending || exchanges > exchanges_seen;
    exchanges_seen = exchanges;
    const bool due = !wanted.empty() && s.step >= *wanted.begin();
    if (s.events.cuts.empty() && (due || exchange_pending) && s.step + 60 <= steps) {
      wanted.erase(wanted.begin(), wanted.upper_bound(s.step));
      exchange_pending = false;
      taken[s.step] = run->comp.runner->snapshot(s);
    }
  }
  const std::vector<std::uint8_t> final_bytes = run->comp.runner->snapshot(s);
  ASSERT_EQ(exchanges_seen, 4u);
  ASSERT_GE(taken.size(), 8u);
  {
    // The report is a function of the scene and the state: a pipeline that has taken no step
    // but adopted the final state reports what the run did, its assessment included.
    SCOPED_TRACE("the final state adopted by a fresh pipeline");
    auto f = build(scene);
    f->comp.runner->restore(final_bytes, f->assembled.state, "snapshot");
    ASSERT_NE(run->comp.metrics, nullptr);
    EXPECT_EQ(f->comp.metrics->report(), run->comp.metrics->report());
    const nlohmann::json graded =
        assessment_report(scene, run->comp.metrics, s.mesh, run->assembled.group_names());
    ASSERT_FALSE(graded.is_null());
    EXPECT_EQ(assessment_report(scene, f->comp.metrics, f->assembled.state.mesh,
                                f->assembled.group_names()),
              graded);
  }
  for (auto it = taken.begin(); it != taken.end(); ++it) {
    SCOPED_TRACE("restored after step " + std::to_string(it->first));
    auto r = build(scene);
    SimState& rs = r->assembled.state;
    r->comp.runner->restore(it->second, rs, "snapshot");
    EXPECT_EQ(r->comp.runner->snapshot(rs), it->second);
    const bool last = std::next(it) == taken.end();
    const std::uint64_t until = last ? steps : it->first + 60;
    while (rs.step < until) {
      r->comp.runner->step(rs);
      ASSERT_EQ(state_hash(rs), hashes.at(rs.step)) << "step " << rs.step;
    }
    if (last) {
      EXPECT_EQ(r->comp.runner->snapshot(rs), final_bytes);
    }
  }
}

TEST(Snapshot, DamagedSnapshotIsAnInputErrorNeverACrash) {
  const Scene scene = load_scene(source("config/beam.toml"));
  auto run = build(scene);
  run->comp.runner->run(run->assembled.state, 3);
  const std::vector<std::uint8_t> bytes = run->comp.runner->snapshot(run->assembled.state);
  std::mt19937 rng(7);
  for (int k = 0; k < 300; ++k) {
    std::vector<std::uint8_t> bad = bytes;
    if (k % 2 == 0) {
      bad.resize(std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(rng));
    } else {
      bad[std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(rng)] ^= 0x5a;
    }
    auto fresh = build(scene);
    try {
      fresh->comp.runner->restore(bad, fresh->assembled.state, "bad.snapshot");
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.snapshot"), std::string::npos) << e.what();
    }
  }
  // Another scene's stages do not take this one's blocks.
  const Scene other = load_scene(source("config/transection.toml"));
  auto o = build(other);
  EXPECT_THROW(o->comp.runner->restore(bytes, o->assembled.state, "beam"), InputError);
}

TEST(Snapshot, ReplayFromATimeStartsAtTheSnapshotBeforeItAndVerifies) {
  const fs::path dir = out_dir("snapshot_replay_from");
  HeadlessOptions h;
  h.scene = source("config/transection.toml");
  h.record = dir / "run.lapr";
  h.progress = false;
  const auto report = run_headless(h);
  ASSERT_GE(report["recording"]["snapshots"].get<int>(), 4);  // every second of 5 s

  ReplayOptions o;
  o.recording = *h.record;
  o.verify = true;
  o.progress = false;
  o.from_s = 3.5;
  const ReplayResult r = run_replay(o);
  EXPECT_EQ(r.start_step, 600u);  // the snapshot after 3.0 s
  EXPECT_EQ(r.report["start_step"].get<std::uint64_t>(), 600u);
  EXPECT_EQ(r.steps, kSteps - 600);
  EXPECT_GT(r.hashes_checked, 0u);
  EXPECT_GE(r.snapshots_checked, 1u);
  EXPECT_FALSE(r.diverged_at.has_value());
  EXPECT_FALSE(r.snapshot_diverged_at.has_value()) << r.snapshot_part;
  EXPECT_TRUE(r.report["verify"]["ok"].get<bool>());
  EXPECT_EQ(r.report["state_hash"], report["state_hash"]);

  // Before the first snapshot: from step 0.
  o.from_s = 0.5;
  const ReplayResult r0 = run_replay(o);
  EXPECT_EQ(r0.start_step, 0u);
  EXPECT_EQ(r0.steps, kSteps);
  EXPECT_TRUE(r0.report["verify"]["ok"].get<bool>());

  // The same run as a build that wrote snapshot version 5 recorded it: the snapshots are skipped
  // and said so, the replay starts from step 0 and verifies the recorded hashes.
  const recording::Recording rec = recording::read_recording(*h.record);
  const fs::path old = dir / "old.lapr";
  {
    recording::RecordingWriter w(old, rec.header);
    for (std::uint64_t k = 0; k < rec.inputs.size(); ++k) {
      w.record_inputs(k, rec.inputs[k]);
      if (const auto it = rec.hashes.find(k); it != rec.hashes.end()) w.record_hash(k, it->second);
      if (const auto it = rec.snapshots.find(k + 1); it != rec.snapshots.end()) {
        std::vector<std::uint8_t> v5 = it->second;
        v5[4] = 5;  // the version, after "SNAP"
        w.record_snapshot(k + 1, v5);
      }
    }
    w.close(rec.inputs.size());
  }
  o.recording = old;
  o.from_s = 3.5;
  const ReplayResult r5 = run_replay(o);
  EXPECT_EQ(r5.start_step, 0u);
  EXPECT_EQ(r5.snapshots_checked, 0u);
  EXPECT_GT(r5.hashes_checked, 0u);
  EXPECT_TRUE(r5.report["verify"]["ok"].get<bool>());
  ASSERT_TRUE(r5.report.contains("warnings"));
  EXPECT_EQ(r5.report["warnings"][0]["kind"], "old_snapshots");
  EXPECT_NE(r5.report["warnings"][0]["text"].get<std::string>().find("version 5"),
            std::string::npos);
}

}  // namespace
}  // namespace serosa::app
