// .lapr recordings: round trip, damage anywhere after the header reads up to the last good chunk
// and names the offset, the writer flushes while the run goes on.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>

#include "engine/input_error.h"
#include "recording/recording_reader.h"
#include "recording/recording_writer.h"
#include "support/file_bytes.h"

namespace serosa::recording {
namespace {

namespace fs = std::filesystem;

fs::path temp_file(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("serosa_rec_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

using test_support::bytes_of;

ToolState tool(std::uint64_t step, int k) {
  ToolState t;
  t.tick = step;
  t.time_s = 0.005 * static_cast<double>(step);
  t.tip_m = {0.01 * k, -0.002 * static_cast<double>(step), 1.0 / 3.0};
  t.quat_wxyz = {0.5, 0.5, -0.5, 0.5};
  t.jaw_rad = 0.25 * k;
  t.buttons = static_cast<std::uint32_t>(step % 3);
  return t;
}

Header header() {
  Header h;
  h.set("serosa", "test");
  h.set("scene_text", "[scene]\ndt = 0.005\n# \xc3\xa9\0 binary-safe");
  h.set("tools", "a,b");
  return h;
}

// Writes `steps` steps with a hash every 10, a chunk every `per_chunk` steps (small chunks).
fs::path write_run(const std::string& name, std::uint64_t steps, bool close = true) {
  const fs::path p = temp_file(name);
  WriterOptions o;
  o.chunk_bytes = 600;  // a few steps per chunk
  RecordingWriter w(p, header(), o);
  for (std::uint64_t s = 0; s < steps; ++s) {
    const std::vector<ToolState> tools{tool(s, 0), tool(s, 1)};
    w.record_inputs(s, tools);
    if ((s + 1) % 10 == 0) w.record_hash(s, s * 7919u);
    if (s == 5) w.record_event(s, "pause");
  }
  if (close) {
    w.close(steps);
  } else {
    w.abandon();
  }
  return p;
}

TEST(Recording, RoundTripsBitForBit) {
  const fs::path p = write_run("round.lapr", 100);
  const Recording r = read_recording(p);
  EXPECT_TRUE(r.complete) << r.stopped;
  EXPECT_TRUE(r.stopped.empty()) << r.stopped;
  EXPECT_EQ(r.header.get("scene_text"), header().get("scene_text"));
  EXPECT_EQ(r.header.get("tools"), "a,b");
  ASSERT_EQ(r.inputs.size(), 100u);
  for (std::uint64_t s = 0; s < 100; ++s)
    for (int k = 0; k < 2; ++k) {
      const ToolState a = r.inputs[s][static_cast<std::size_t>(k)], b = tool(s, k);
      EXPECT_EQ(std::memcmp(&a.tip_m, &b.tip_m, sizeof a.tip_m), 0);
      EXPECT_EQ(a.tick, b.tick);
      EXPECT_EQ(a.time_s, b.time_s);
      EXPECT_EQ(a.quat_wxyz, b.quat_wxyz);
      EXPECT_EQ(a.jaw_rad, b.jaw_rad);
      EXPECT_EQ(a.buttons, b.buttons);
    }
  ASSERT_EQ(r.hashes.size(), 10u);
  EXPECT_EQ(r.hashes.at(99), 99u * 7919u);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].second, "pause");
  EXPECT_GT(r.chunks, 5);
}

// Snapshots (version 2) round-trip, whatever their size against the chunk size; a version-1 file
// (no snapshots; the version field is the only header difference) still reads.
TEST(Recording, SnapshotsRoundTripAndVersionOneStillReads) {
  const fs::path p = temp_file("snap.lapr");
  {
    WriterOptions o;
    o.chunk_bytes = 600;
    RecordingWriter w(p, header(), o);
    for (std::uint64_t s = 0; s < 30; ++s) {
      const std::vector<ToolState> tools{tool(s, 0), tool(s, 1)};
      w.record_inputs(s, tools);
      if ((s + 1) % 10 == 0) {
        std::vector<std::uint8_t> snap(100 * (s + 1));
        for (std::size_t i = 0; i < snap.size(); ++i)
          snap[i] = static_cast<std::uint8_t>(i * 31 + s);
        w.record_snapshot(s + 1, snap);
      }
    }
    EXPECT_EQ(w.stats().snapshots, 3u);
    w.close(30);
  }
  const Recording r = read_recording(p);
  EXPECT_TRUE(r.complete) << r.stopped;
  EXPECT_EQ(r.version, kVersion);
  ASSERT_EQ(r.snapshots.size(), 3u);
  for (const auto& [steps, snap] : r.snapshots) {
    ASSERT_EQ(snap.size(), 100 * steps);
    for (std::size_t i = 0; i < snap.size(); ++i)
      ASSERT_EQ(snap[i], static_cast<std::uint8_t>(i * 31 + (steps - 1)));
  }
  const fs::path old = write_run("v1.lapr", 20);
  std::vector<std::uint8_t> b = bytes_of(old);
  b[4] = 1;  // the version field; its header checksum covers the key/value bytes only
  const Recording r1 = parse_recording(b, "v1.lapr");
  EXPECT_EQ(r1.version, 1u);
  EXPECT_TRUE(r1.complete) << r1.stopped;
  EXPECT_EQ(r1.inputs.size(), 20u);
  EXPECT_TRUE(r1.snapshots.empty());
}

TEST(Recording, EveryTruncationReadsAPrefixAndSaysWhere) {
  const fs::path p = write_run("trunc.lapr", 60);
  const std::vector<std::uint8_t> all = bytes_of(p);
  const Recording full = parse_recording(all, "full");
  std::size_t header_end = 0;
  {
    // The header ends where the first chunk magic starts.
    for (std::size_t i = 0; i + 4 <= all.size(); ++i)
      if (std::equal(kChunkMagic, kChunkMagic + 4, all.begin() + static_cast<std::ptrdiff_t>(i))) {
        header_end = i;
        break;
      }
  }
  ASSERT_GT(header_end, 0u);
  std::size_t previous = 0;
  for (std::size_t n = header_end; n < all.size(); ++n) {
    const std::vector<std::uint8_t> cut(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(n));
    const Recording r = parse_recording(cut, "cut");
    EXPECT_FALSE(r.complete);
    EXPECT_FALSE(r.stopped.empty());
    EXPECT_LE(r.stopped_at, n);
    // What was read is a prefix of the full run, growing with the file.
    ASSERT_LE(r.inputs.size(), full.inputs.size());
    EXPECT_GE(r.inputs.size(), previous);
    previous = r.inputs.size();
    for (std::size_t s = 0; s < r.inputs.size(); ++s)
      EXPECT_EQ(r.inputs[s][0].tip_m, full.inputs[s][0].tip_m);
  }
  EXPECT_GT(previous, 40u);
}

TEST(Recording, CorruptByteIsFoundAndNamed) {
  const fs::path p = write_run("corrupt.lapr", 60);
  const std::vector<std::uint8_t> all = bytes_of(p);
  const Recording full = parse_recording(all, "full");
  std::mt19937 rng(5);
  const std::size_t header_end = all.size() / 2;  // flips in the second half of the file
  for (int trial = 0; trial < 200; ++trial) {
    std::uniform_int_distribution<std::size_t> pick(header_end, all.size() - 1);
    const std::size_t at = pick(rng);
    std::vector<std::uint8_t> bad = all;
    bad[at] ^= static_cast<std::uint8_t>(1u << (trial % 8));
    const Recording r = parse_recording(bad, "bad");
    EXPECT_FALSE(r.complete) << "flip at " << at;
    EXPECT_NE(r.stopped.find("at byte " + std::to_string(r.stopped_at)), std::string::npos)
        << r.stopped;
    // It stopped at the chunk holding the flipped byte: at or before it, within one chunk.
    EXPECT_LE(r.stopped_at, at);
    EXPECT_LT(at - r.stopped_at, 1000u);
    for (std::size_t s = 0; s < r.inputs.size(); ++s)
      EXPECT_EQ(r.inputs[s][1].jaw_rad, full.inputs[s][1].jaw_rad);
  }
}

TEST(Recording, DamagedHeaderOrWrongFileIsAnInputError) {
  const fs::path p = write_run("head.lapr", 5);
  std::vector<std::uint8_t> b = bytes_of(p);
  b[20] ^= 0x40;
  EXPECT_THROW((void)parse_recording(b, "x"), InputError);
  EXPECT_THROW((void)parse_recording({'M', 'Z', 0, 0}, "x"), InputError);
  std::vector<std::uint8_t> v = bytes_of(p);
  v[4] = 99;  // version
  try {
    (void)parse_recording(v, "x.lapr");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("version 99"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)read_recording(temp_file("missing.lapr")), InputError);
}

// A directory opens as a stream whose end lies at 2^63 - 1 on ext4: a reader sizing its buffer
// from that asked for 8 EiB (std::bad_alloc) instead of saying what is wrong.
TEST(Recording, ADirectoryIsAnInputErrorNamingIt) {
  const fs::path dir = temp_file("a_directory.lapr");
  fs::create_directories(dir);
  try {
    (void)read_recording(dir);
    FAIL() << "read a directory";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), dir.string());
    EXPECT_NE(e.message().find("is a directory"), std::string::npos) << e.what();
  }
}

TEST(Recording, AbandonedRunKeepsItsStepsWithoutEnd) {
  const Recording r = read_recording(write_run("abandon.lapr", 30, false));
  EXPECT_FALSE(r.complete);
  EXPECT_EQ(r.inputs.size(), 30u);
  EXPECT_NE(r.stopped.find("no end record"), std::string::npos) << r.stopped;
}

TEST(Recording, WriterFlushesWhileTheRunGoesOn) {
  const fs::path p = temp_file("live.lapr");
  WriterOptions o;
  o.flush_interval = std::chrono::milliseconds(50);
  RecordingWriter w(p, header(), o);
  const std::vector<ToolState> tools{tool(0, 0)};
  w.record_inputs(0, tools);
  // Without closing, the step reaches the file (poll: the machine may be busy).
  std::size_t seen = 0;
  for (int i = 0; i < 200 && seen == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
    seen = parse_recording(bytes_of(p), "live").inputs.size();
  }
  EXPECT_EQ(seen, 1u);
  w.close(1);
  EXPECT_TRUE(read_recording(p).complete);
}

}  // namespace
}  // namespace serosa::recording
