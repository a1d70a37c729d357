// Recording and replay end to end: record then replay --verify is bit-identical; a tampered hash
// is a divergence naming its step; a corrupt byte is reported with its offset; kill -9 while
// recording (the real `serosa` process) leaves a file that replays up to its last chunk.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "app/headless.h"
#include "app_test_util.h"
#include "recording/recording_reader.h"
#include "recording/recording_writer.h"
#include "replay/replay.h"
#include "support/file_bytes.h"

namespace serosa::app {
namespace {

using namespace serosa::replay;

using namespace serosa::app::testing;

using test_support::bytes_of;

// A 40-step scripted transection, recorded (hash every 20 steps, from the scene).
struct Recorded {
  fs::path file;
  nlohmann::json report;
};
Recorded record_transection(const fs::path& dir) {
  HeadlessOptions o;
  o.scene = source("config/transection.toml");
  o.tool_path = source("config/paths/appendix_transection.csv");
  o.steps = 40;
  o.record = dir / "run.lapr";
  o.progress = false;
  return {*o.record, run_headless(o)};
}

TEST(RecordReplay, ReplayVerifyIsBitIdentical) {
  const fs::path dir = out_dir("record_replay");
  const Recorded rec = record_transection(dir);
  ASSERT_GT(rec.report["cutting"]["cuts"].get<int>(), 0);
  EXPECT_EQ(rec.report["recording"]["steps"], 40);

  ReplayOptions o;
  o.recording = rec.file;
  o.verify = true;
  o.progress = false;
  const ReplayResult r = run_replay(o);
  EXPECT_EQ(r.steps, 40u);
  EXPECT_EQ(r.hashes_checked, 2u);
  EXPECT_FALSE(r.diverged_at.has_value());
  EXPECT_TRUE(r.damage.empty()) << r.damage;
  // The final state is the same bit for bit, and so is what cutting did.
  EXPECT_EQ(r.report["state_hash"], rec.report["state_hash"]);
  EXPECT_EQ(r.report["cutting"], rec.report["cutting"]);
  // The replay scores the session again, as the run did.
  ASSERT_TRUE(rec.report.contains("assessment"));
  EXPECT_EQ(r.report["assessment"], rec.report["assessment"]);

  // The CLI agrees: exit 0.
  const CliResult cli = run_serosa("replay '" + rec.file.string() + "' --headless --verify");
  EXPECT_EQ(cli.code, 0) << cli.out;
}

TEST(RecordReplay, TamperedHashIsADivergenceNamingItsStep) {
  const fs::path dir = out_dir("record_tampered");
  const Recorded rec = record_transection(dir);
  // Re-encode the recording with the second hash changed (checksums stay valid).
  recording::Recording r = recording::read_recording(rec.file);
  ASSERT_EQ(r.hashes.size(), 2u);
  r.hashes.rbegin()->second ^= 1u;
  const fs::path bad = dir / "tampered.lapr";
  {
    recording::RecordingWriter w(bad, r.header);
    for (std::uint64_t s = 0; s < r.inputs.size(); ++s) {
      w.record_inputs(s, r.inputs[s]);
      if (auto it = r.hashes.find(s); it != r.hashes.end()) w.record_hash(s, it->second);
    }
    w.close(r.inputs.size());
  }
  const CliResult cli = run_serosa("replay '" + bad.string() + "' --headless --verify");
  EXPECT_EQ(cli.code, 3) << cli.out;
  EXPECT_NE(cli.out.find("diverged from the recording at step 39"), std::string::npos) << cli.out;
}

TEST(RecordReplay, CorruptByteIsReportedWithItsOffset) {
  const fs::path dir = out_dir("record_corrupt");
  const Recorded rec = record_transection(dir);
  std::vector<std::uint8_t> b = bytes_of(rec.file);
  const std::size_t at = b.size() - 40;  // inside the last chunk
  b[at] ^= 0x10;
  const fs::path bad = dir / "corrupt.lapr";
  std::ofstream(bad, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  const recording::Recording r = recording::read_recording(bad);
  ASSERT_TRUE(r.corrupt) << r.stopped;
  EXPECT_LE(r.stopped_at, at);
  const CliResult cli = run_serosa("replay '" + bad.string() + "' --headless --verify");
  EXPECT_EQ(cli.code, 4) << cli.out;
  EXPECT_NE(cli.out.find("checksum mismatch in chunk at byte " + std::to_string(r.stopped_at)),
            std::string::npos)
      << cli.out;
}

TEST(RecordReplay, KillNineWhileRecordingReplaysUpToTheLastChunk) {
  const fs::path dir = out_dir("record_kill");
  const fs::path file = dir / "killed.lapr";
  const std::string exe = serosa_exe().string();
  const std::string scene = source("config/beam.toml").string();
  const std::string path = file.string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // The child: a long headless run, recording; its output goes nowhere.
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    execl(exe.c_str(), exe.c_str(), "headless", scene.c_str(), "--steps", "100000000", "--record",
          path.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until the writer thread has flushed a few chunks, then kill -9.
  std::int64_t chunks = 0;
  for (int i = 0; i < 600 && chunks < 3; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (fs::exists(file) && fs::file_size(file) > 0) {
      try {
        chunks = recording::read_recording(file).chunks;
      } catch (const std::exception&) {  // header not complete yet
      }
    }
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_GE(chunks, 3) << "the recording never reached 3 chunks";

  const recording::Recording r = recording::read_recording(file);
  EXPECT_FALSE(r.complete);
  EXPECT_FALSE(r.corrupt) << r.stopped;
  ASSERT_GT(r.inputs.size(), 0u);
  const CliResult cli = run_serosa("replay '" + path + "' --headless --verify");
  EXPECT_EQ(cli.code, 0) << cli.out;
  EXPECT_NE(cli.out.find("replayed " + std::to_string(r.inputs.size()) + " steps"),
            std::string::npos)
      << cli.out;
}

// Starts `serosa headless SCENE --steps 1e8 --record FILE [extra]` in a child process and
// returns its pid once the writer has written at least `chunks` chunks (or 60 s passed).
pid_t start_long_recording(const fs::path& file, const std::vector<std::string>& extra,
                           std::int64_t chunks, std::int64_t& seen) {
  const std::string exe = serosa_exe().string();
  const std::string scene = source("config/beam.toml").string();
  const std::string path = file.string();
  std::vector<std::string> args{exe, "headless", scene, "--steps", "100000000", "--record", path};
  args.insert(args.end(), extra.begin(), extra.end());
  const pid_t pid = fork();
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(exe.c_str(), argv.data());
    _exit(127);
  }
  seen = 0;
  for (int i = 0; i < 600 && seen < chunks; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (fs::exists(file) && fs::file_size(file) > 0) {
      try {
        seen = recording::read_recording(file).chunks;
      } catch (const std::exception&) {  // header not complete yet
      }
    }
  }
  return pid;
}

TEST(RecordReplay, CtrlCWhileRecordingClosesTheRecordingCleanly) {
  const fs::path dir = out_dir("record_sigint");
  const fs::path file = dir / "interrupted.lapr";
  const fs::path report = dir / "report.json";
  std::int64_t chunks = 0;
  const pid_t pid = start_long_recording(file, {"--report", report.string()}, 2, chunks);
  ASSERT_GT(pid, 0);
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_GE(chunks, 2) << "the recording never reached 2 chunks";
  // The run ends after the current step: exit 0, recording complete with its end record, the
  // report written and saying it was interrupted.
  ASSERT_TRUE(WIFEXITED(status)) << "status " << status;
  EXPECT_EQ(WEXITSTATUS(status), 0);
  const recording::Recording r = recording::read_recording(file);
  EXPECT_TRUE(r.complete) << r.stopped;
  EXPECT_FALSE(r.corrupt);
  EXPECT_TRUE(r.stopped.empty()) << r.stopped;
  ASSERT_TRUE(fs::exists(report));
  nlohmann::json j;
  std::ifstream(report) >> j;
  EXPECT_TRUE(j["interrupted"].get<bool>());
  EXPECT_EQ(j["steps_taken"].get<std::uint64_t>(), r.inputs.size());
  EXPECT_EQ(j["recording"]["steps"].get<std::uint64_t>(), r.inputs.size());
  // It replays in full and verifies: no "cut short" warning.
  const CliResult cli = run_serosa("replay '" + file.string() + "' --headless --verify");
  EXPECT_EQ(cli.code, 0) << cli.out;
  EXPECT_EQ(cli.out.find("warning"), std::string::npos) << cli.out;
}

TEST(RecordReplay, NotARecordingIsAClearError) {
  const fs::path dir = out_dir("record_bad");
  std::ofstream(dir / "x.lapr") << "hello";
  const CliResult cli = run_serosa("replay '" + (dir / "x.lapr").string() + "' --headless");
  EXPECT_EQ(cli.code, 1) << cli.out;
  EXPECT_NE(cli.out.find("not a Serosa recording"), std::string::npos) << cli.out;
}

}  // namespace
}  // namespace serosa::app
