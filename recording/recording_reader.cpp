#include "recording/recording_reader.h"

#include <algorithm>
#include <bit>
#include <fstream>
#include <iterator>
#include <optional>
#include <system_error>

#include "engine/input_error.h"

namespace serosa::recording {
namespace {

// Bounds-checked little-endian reads over [pos, end).
class Cursor {
 public:
  Cursor(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
  [[nodiscard]] std::size_t pos() const { return m_pos; }
  [[nodiscard]] std::size_t left() const { return m_size - m_pos; }
  bool u8(std::uint8_t& v) {
    if (left() < 1) return false;
    v = m_data[m_pos++];
    return true;
  }
  bool u32(std::uint32_t& v) {
    if (left() < 4) return false;
    v = 0;
    for (int i = 0; i < 4; ++i)
      v |= std::uint32_t{m_data[m_pos + static_cast<std::size_t>(i)]} << (8 * i);
    m_pos += 4;
    return true;
  }
  bool u64(std::uint64_t& v) {
    if (left() < 8) return false;
    v = 0;
    for (int i = 0; i < 8; ++i)
      v |= std::uint64_t{m_data[m_pos + static_cast<std::size_t>(i)]} << (8 * i);
    m_pos += 8;
    return true;
  }
  bool f64(double& v) {
    std::uint64_t u = 0;
    if (!u64(u)) return false;
    v = std::bit_cast<double>(u);
    return true;
  }
  bool str(std::string& s) {
    std::uint32_t n = 0;
    if (!u32(n) || left() < n) return false;
    s.assign(reinterpret_cast<const char*>(m_data + m_pos), n);
    m_pos += n;
    return true;
  }
  void skip(std::size_t n) { m_pos += n; }
  bool tool(ToolState& t) {
    bool ok = u64(t.tick) && f64(t.time_s);
    for (double& c : t.tip_m) ok = ok && f64(c);
    for (double& c : t.quat_wxyz) ok = ok && f64(c);
    return ok && f64(t.jaw_rad) && u32(t.buttons);
  }

 private:
  const std::uint8_t* m_data;
  std::size_t m_size;
  std::size_t m_pos = 0;
};

std::string at(std::size_t offset) {
  std::string s = "at byte ";
  s.append(std::to_string(offset));
  return s;
}

// Decodes one chunk's records into `rec`; returns an error message or nullopt.
// Input steps must continue from `base` (the steps read before this chunk).
std::optional<std::string> decode_payload(const std::uint8_t* p, std::size_t n, std::size_t base,
                                          Recording& rec, bool& ended) {
  Cursor c(p, n);
  while (c.left() > 0) {
    std::uint8_t type = 0;
    (void)c.u8(type);
    std::uint64_t step = 0;
    if (!c.u64(step)) return "record cut short";
    switch (static_cast<RecordType>(type)) {
      case RecordType::kInputs: {
        std::uint32_t k = 0;
        if (!c.u32(k) || c.left() / kToolStateBytes < k) return "input record cut short";
        if (step != base + rec.inputs.size()) {
          std::string e = "inputs of step ";
          e.append(std::to_string(step)).append(" where step ");
          e.append(std::to_string(base + rec.inputs.size())).append(" was expected");
          return e;
        }
        std::vector<ToolState> tools(k);
        for (ToolState& t : tools) (void)c.tool(t);
        rec.inputs.push_back(std::move(tools));
        break;
      }
      case RecordType::kHash: {
        std::uint64_t h = 0;
        if (!c.u64(h)) return "hash record cut short";
        rec.hashes[step] = h;
        break;
      }
      case RecordType::kEvent: {
        std::string text;
        if (!c.str(text)) return "event record cut short";
        rec.events.emplace_back(step, std::move(text));
        break;
      }
      case RecordType::kEnd:
        ended = true;
        break;
      case RecordType::kSnapshot: {
        std::uint64_t len = 0;
        if (!c.u64(len) || c.left() < len) return "snapshot record cut short";
        const std::uint8_t* b = p + c.pos();
        rec.snapshots[step].assign(b, b + len);
        c.skip(static_cast<std::size_t>(len));
        break;
      }
      default:
        return "unknown record type " + std::to_string(type);
    }
  }
  return std::nullopt;
}

}  // namespace

Recording parse_recording(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  Recording rec;
  Cursor c(bytes.data(), bytes.size());
  // ---- header: any damage here is fatal ----
  if (bytes.size() < 4 || !std::equal(kFileMagic, kFileMagic + 4, bytes.begin()))
    throw InputError(name, 0, "not a Serosa recording (no LAPR magic at byte 0)",
                     "a .lapr file written by serosa --record");
  std::uint32_t hlen = 0;
  std::uint32_t crc = 0;
  (void)c.u32(hlen);  // skip magic
  if (!c.u32(rec.version)) throw InputError(name, 0, "file cut short in the header");
  if (rec.version < kOldestVersion || rec.version > kVersion)
    throw InputError(
        name, 0, "recording format version " + std::to_string(rec.version),
        "version " + std::to_string(kOldestVersion) + " to " + std::to_string(kVersion));
  if (!c.u32(hlen) || hlen > kMaxHeader || c.left() < std::size_t{hlen} + 4)
    throw InputError(name, 0, "file cut short in the header (at byte 12)");
  const std::size_t body = c.pos();
  {
    Cursor h(bytes.data() + body, hlen);
    std::uint32_t count = 0;
    bool ok = h.u32(count);
    for (std::uint32_t i = 0; ok && i < count; ++i) {
      std::string k, v;
      ok = h.str(k) && h.str(v);
      if (ok) rec.header.fields.emplace_back(std::move(k), std::move(v));
    }
    Cursor tail(bytes.data() + body + hlen, 4);
    (void)tail.u32(crc);
    if (!ok || crc != crc32(std::span(bytes.data() + body, hlen)))
      throw InputError(name, 0, "header damaged (checksum mismatch " + at(body) + ")");
  }
  std::size_t pos = body + hlen + 4;

  // ---- chunks: stop at the first damaged one ----
  bool ended = false;
  while (pos < bytes.size()) {
    if (ended) {
      rec.stopped = "data after the end record " + at(pos);
      rec.corrupt = true;
      break;
    }
    Cursor k(bytes.data() + pos, bytes.size() - pos);
    std::uint32_t magic = 0, len = 0, sum = 0;
    if (!k.u32(magic) || !k.u32(len) || !k.u32(sum)) {
      rec.stopped = "chunk header cut short " + at(pos);
      break;
    }
    if (!std::equal(kChunkMagic, kChunkMagic + 4,
                    bytes.begin() + static_cast<std::ptrdiff_t>(pos))) {
      rec.stopped = "bad chunk magic " + at(pos);
      rec.corrupt = true;
      break;
    }
    if (len > kMaxChunkPayload) {
      rec.stopped = "implausible chunk length " + std::to_string(len) + " " + at(pos);
      rec.corrupt = true;
      break;
    }
    if (k.left() < len) {
      rec.stopped = "chunk cut short " + at(pos) + " (" + std::to_string(k.left()) + " of " +
                    std::to_string(len) + " payload bytes)";
      break;
    }
    const std::uint8_t* payload = bytes.data() + pos + 12;
    if (crc32(std::span(payload, len)) != sum) {
      rec.stopped = "checksum mismatch in chunk " + at(pos);
      rec.corrupt = true;
      break;
    }
    // Decode apart so that a bad record drops its whole chunk, not half of it.
    Recording part;
    bool part_ended = false;
    if (auto err = decode_payload(payload, len, rec.inputs.size(), part, part_ended)) {
      rec.stopped = *err;
      rec.stopped.append(" in chunk ").append(at(pos));
      rec.corrupt = true;
      break;
    }
    for (auto& in : part.inputs) rec.inputs.push_back(std::move(in));
    rec.hashes.insert(part.hashes.begin(), part.hashes.end());
    for (auto& e : part.events) rec.events.push_back(std::move(e));
    for (auto& [steps, snap] : part.snapshots) rec.snapshots[steps] = std::move(snap);
    ended = part_ended;
    ++rec.chunks;
    pos += 12 + std::size_t{len};
  }
  rec.stopped_at = rec.stopped.empty() ? bytes.size() : pos;
  rec.complete = ended && rec.stopped.empty();
  if (!ended && rec.stopped.empty())
    rec.stopped = "no end record: the run was cut short " + at(pos);
  return rec;
}

Recording read_recording(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  // A directory opens as a stream, and seeking to its end says 2^63 - 1 (ext4): it must be
  // refused before reading, and the read must not be sized from a seek.
  if (fs::is_directory(st))
    throw InputError(path.string(), 0, "is a directory", "a .lapr file written by serosa --record");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "recording not found or unreadable");
  // Read in chunks: regular files and pipes alike, never more than there is.
  std::vector<std::uint8_t> bytes;
  if (fs::is_regular_file(st)) {
    const std::uintmax_t size = fs::file_size(path, ec);
    if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  }
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0)
    bytes.insert(bytes.end(), chunk, chunk + in.gcount());
  if (in.bad()) throw InputError(path.string(), 0, "read error", "a readable .lapr file");
  return parse_recording(bytes, path.string());
}

}  // namespace serosa::recording
