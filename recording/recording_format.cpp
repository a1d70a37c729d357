#include "recording/recording_format.h"

#include <array>
#include <bit>
#include <cstring>

namespace serosa::recording {
namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[i] = c;
  }
  return t;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

}  // namespace

std::string Header::get(const std::string& key) const {
  for (const auto& [k, v] : fields)
    if (k == key) return v;
  return {};
}

void Header::set(const std::string& key, std::string value) {
  for (auto& [k, v] : fields)
    if (k == key) {
      v = std::move(value);
      return;
    }
  fields.emplace_back(key, std::move(value));
}

std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc) {
  crc = ~crc;
  for (std::uint8_t b : bytes) crc = kCrcTable[(crc ^ b) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

void put_u8(std::vector<std::uint8_t>& out, std::uint8_t v) { out.push_back(v); }
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_u64(std::vector<std::uint8_t>& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_f64(std::vector<std::uint8_t>& out, double v) {
  put_u64(out, std::bit_cast<std::uint64_t>(v));
}
void put_string(std::vector<std::uint8_t>& out, const std::string& s) {
  put_u32(out, static_cast<std::uint32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}
void put_tool_state(std::vector<std::uint8_t>& out, const ToolState& t) {
  put_u64(out, t.tick);
  put_f64(out, t.time_s);
  for (double c : t.tip_m) put_f64(out, c);
  for (double c : t.quat_wxyz) put_f64(out, c);
  put_f64(out, t.jaw_rad);
  put_u32(out, t.buttons);
}

std::vector<std::uint8_t> encode_header(const Header& h) {
  std::vector<std::uint8_t> body;
  put_u32(body, static_cast<std::uint32_t>(h.fields.size()));
  for (const auto& [k, v] : h.fields) {
    put_string(body, k);
    put_string(body, v);
  }
  std::vector<std::uint8_t> out(kFileMagic, kFileMagic + 4);
  put_u32(out, kVersion);
  put_u32(out, static_cast<std::uint32_t>(body.size()));
  out.insert(out.end(), body.begin(), body.end());
  put_u32(out, crc32(body));
  return out;
}

std::vector<std::uint8_t> encode_chunk(std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out(kChunkMagic, kChunkMagic + 4);
  out.reserve(12 + payload.size());
  put_u32(out, static_cast<std::uint32_t>(payload.size()));
  put_u32(out, crc32(payload));
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

void put_inputs(std::vector<std::uint8_t>& out, std::uint64_t step,
                std::span<const ToolState> tools) {
  put_u8(out, static_cast<std::uint8_t>(RecordType::kInputs));
  put_u64(out, step);
  put_u32(out, static_cast<std::uint32_t>(tools.size()));
  for (const ToolState& t : tools) put_tool_state(out, t);
}

void put_hash(std::vector<std::uint8_t>& out, std::uint64_t step, std::uint64_t hash) {
  put_u8(out, static_cast<std::uint8_t>(RecordType::kHash));
  put_u64(out, step);
  put_u64(out, hash);
}

void put_event(std::vector<std::uint8_t>& out, std::uint64_t step, const std::string& text) {
  put_u8(out, static_cast<std::uint8_t>(RecordType::kEvent));
  put_u64(out, step);
  put_string(out, text);
}

void put_snapshot(std::vector<std::uint8_t>& out, std::uint64_t steps,
                  std::span<const std::uint8_t> snapshot) {
  put_u8(out, static_cast<std::uint8_t>(RecordType::kSnapshot));
  put_u64(out, steps);
  put_u64(out, snapshot.size());
  out.insert(out.end(), snapshot.begin(), snapshot.end());
}

void put_end(std::vector<std::uint8_t>& out, std::uint64_t steps) {
  put_u8(out, static_cast<std::uint8_t>(RecordType::kEnd));
  put_u64(out, steps);
}

}  // namespace serosa::recording
