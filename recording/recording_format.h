// The .lapr recording format (docs/recording-format.md): what one run's solver consumed, step by
// step, plus periodic state hashes, so that a replay re-simulates it bit for bit and checks it.
//
//   file   := header chunk*
//   header := "LAPR" u32:version u32:header_len header_bytes u32:crc32(header_bytes)
//   header_bytes := u32:count (u32:key_len key u32:value_len value){count}   (UTF-8 strings)
//   chunk  := "CHNK" u32:payload_len u32:crc32(payload) payload
//   payload:= record*
//   record := u8:type ...   kInputs: u64:step u32:num_tools ToolState{num_tools}
//                           kHash:   u64:step u64:state_hash (after the step's stages)
//                           kEvent:  u64:step u32:len text
//                           kEnd:    u64:steps (the run ended cleanly after this many steps)
//                           kSnapshot: u64:steps u64:len bytes (the whole state after that many
//                                    steps, engine/state_codec.h; version 2 on)
//   ToolState := u64:tick f64:time_s f64[3]:tip_m f64[4]:quat_wxyz f64:jaw_rad u32:buttons
// Every integer and float is little-endian (IEEE 754 binary64 for f64). CRC-32 is the
// ISO-HDLC/zlib one (reflected polynomial 0xEDB88320, init and final xor 0xFFFFFFFF).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "engine/tool_state.h"

namespace serosa::recording {

inline constexpr char kFileMagic[4] = {'L', 'A', 'P', 'R'};
inline constexpr char kChunkMagic[4] = {'C', 'H', 'N', 'K'};
inline constexpr std::uint32_t kVersion = 2;
/// The oldest version read (1: no snapshots; it replays from step 0).
inline constexpr std::uint32_t kOldestVersion = 1;
/// A chunk's payload is never larger than this (a reader treats a larger length as corrupt).
inline constexpr std::uint32_t kMaxChunkPayload = 64u << 20;
/// A header is never larger than this.
inline constexpr std::uint32_t kMaxHeader = 64u << 20;
/// Bytes of one encoded ToolState.
inline constexpr std::size_t kToolStateBytes = 8 + 8 + 3 * 8 + 4 * 8 + 8 + 4;

enum class RecordType : std::uint8_t {
  kInputs = 1,
  kHash = 2,
  kEvent = 3,
  kEnd = 4,
  kSnapshot = 5
};

/// The header: ordered key/value strings. Keys written by serosa: "serosa" (version),
/// "scene_path" (absolute path of the scene file), "scene_text" (its whole TOML text), "dt_s",
/// "hash_every", "tools" (comma-separated names, scene order), "created_utc".
struct Header {
  std::vector<std::pair<std::string, std::string>> fields;
  /// The value of `key`, or empty.
  [[nodiscard]] std::string get(const std::string& key) const;
  void set(const std::string& key, std::string value);
};

/// CRC-32 (ISO-HDLC) of bytes, continuing from `crc` (0 to start).
[[nodiscard]] std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);

/// Little-endian appenders (the file's encoding).
void put_u8(std::vector<std::uint8_t>& out, std::uint8_t v);
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v);
void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v);
void put_f64(std::vector<std::uint8_t>& out, double v);
void put_string(std::vector<std::uint8_t>& out, const std::string& s);  ///< u32 length + bytes
void put_tool_state(std::vector<std::uint8_t>& out, const ToolState& t);

/// The whole header block: magic, version, length, bytes, crc.
[[nodiscard]] std::vector<std::uint8_t> encode_header(const Header& h);
/// One chunk around `payload`: magic, length, crc, payload.
[[nodiscard]] std::vector<std::uint8_t> encode_chunk(std::span<const std::uint8_t> payload);

/// Records, appended to a chunk payload.
void put_inputs(std::vector<std::uint8_t>& out, std::uint64_t step,
                std::span<const ToolState> tools);
void put_hash(std::vector<std::uint8_t>& out, std::uint64_t step, std::uint64_t hash);
void put_event(std::vector<std::uint8_t>& out, std::uint64_t step, const std::string& text);
void put_end(std::vector<std::uint8_t>& out, std::uint64_t steps);
void put_snapshot(std::vector<std::uint8_t>& out, std::uint64_t steps,
                  std::span<const std::uint8_t> snapshot);
/// Bytes of a snapshot record around `snapshot_bytes` of snapshot.
[[nodiscard]] constexpr std::size_t snapshot_record_bytes(std::size_t snapshot_bytes) {
  return 1 + 8 + 8 + snapshot_bytes;
}

}  // namespace serosa::recording
