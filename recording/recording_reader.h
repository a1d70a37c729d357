// Reading a .lapr recording (recording/recording_format.h). A damaged file is read up to its last
// good chunk: the reader says where it stopped and why, and what came before stays usable.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "engine/tool_state.h"
#include "recording/recording_format.h"

namespace serosa::recording {

struct Recording {
  Header header;
  std::uint32_t version = 0;
  /// (s) tool inputs of steps 0..s-1, in step order (each of num_tools states).
  std::vector<std::vector<ToolState>> inputs;
  std::map<std::uint64_t, std::uint64_t> hashes;  ///< step -> state hash after that step
  std::vector<std::pair<std::uint64_t, std::string>> events;  ///< (step, text)
  /// steps taken -> the whole state after them (engine/state_codec.h); none before version 2.
  std::map<std::uint64_t, std::vector<std::uint8_t>> snapshots;
  std::int64_t chunks = 0;  ///< good chunks read

  /// The run ended cleanly (end record read, no damage).
  bool complete = false;
  /// Empty when the whole file was read; else why reading stopped, naming the byte offset.
  std::string stopped;
  /// The damage is corruption (bad checksum, magic, length or record), not a run cut short (a
  /// partial last chunk or a missing end record, as after a crash or kill -9).
  bool corrupt = false;
  /// Byte offset of the first byte not used (the damaged chunk's start), or the file size.
  std::uint64_t stopped_at = 0;
};

/// Reads `path`. Throws InputError (naming the file) when it is missing, not a .lapr file, of
/// another version, or its header is damaged: nothing can be replayed then. Damage after the
/// header (truncated or corrupt chunk, bad record, steps out of order) ends the read at the last
/// good chunk and is described in Recording::stopped.
[[nodiscard]] Recording read_recording(const std::filesystem::path& path);

/// Same on bytes in memory; `name` stands for the file in messages.
[[nodiscard]] Recording parse_recording(const std::vector<std::uint8_t>& bytes,
                                        const std::string& name);

}  // namespace serosa::recording
