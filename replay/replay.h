// Instructor replay of a .lapr recording (docs/recording-format.md): rebuilds the scene
// from the text in the recording's header, feeds the recorded tool inputs back step by step and,
// with verify, checks every recorded state hash and compares every recorded whole-state snapshot
// (engine/state_codec.h) with the replayed one. From a time T (--from), it restores the last
// snapshot at or before T and replays from there. A damaged recording replays up to its last good
// chunk; the result says where it stopped.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace serosa::replay {

struct ReplayOptions {
  std::filesystem::path recording;              ///< the .lapr file
  bool verify = false;                          ///< check every recorded state hash
  std::optional<std::filesystem::path> frames;  ///< folder for PNG pictures
  int frame_count = 5;                          ///< pictures over the replay, with frames
  bool fitted_camera = false;  ///< the pictures from a fitted camera, not the endoscope
  std::optional<std::filesystem::path> report;  ///< JSON report
  bool progress = true;                         ///< progress bar on a terminal
  /// Start at simulated time t, s: restore the recording's last snapshot at or before it and
  /// replay (and verify) from there. Without a snapshot that early, from step 0.
  std::optional<double> from_s;
};

struct ReplayResult {
  nlohmann::json report;
  std::uint64_t start_step = 0;      ///< steps already taken in the restored snapshot (0: none)
  std::uint64_t steps = 0;           ///< steps replayed
  std::uint64_t hashes_checked = 0;  ///< recorded hashes compared (verify)
  /// The first step whose state hash differs from the recording's (verify), if any.
  std::optional<std::uint64_t> diverged_at;
  std::uint64_t snapshots_checked = 0;  ///< recorded snapshots compared whole (verify)
  /// Steps taken at the first recorded snapshot the replayed state differs from (verify), and
  /// the part that differs first ("state" or a stage's name).
  std::optional<std::uint64_t> snapshot_diverged_at;
  std::string snapshot_part;
  std::string damage;    ///< empty, or where and why reading the recording stopped
  bool corrupt = false;  ///< the damage is corruption, not a run cut short
};

/// Replays the recording. Throws InputError when the file is not a usable recording (missing,
/// wrong magic or version, damaged header, scene unreadable, tool count differs from the scene).
[[nodiscard]] ReplayResult run_replay(const ReplayOptions& options);

}  // namespace serosa::replay
