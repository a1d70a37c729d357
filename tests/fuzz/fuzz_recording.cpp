// libFuzzer target: the .lapr recording reader on arbitrary bytes (a recording from another
// machine). A damaged header is an InputError naming the file; damage after it ends the read at
// the last good chunk and says where. Nothing else may escape, crash, hang or allocate more than
// the input can justify (libFuzzer's -rss_limit_mb and -malloc_limit_mb catch that).
//
// Every header and chunk carries a CRC-32, which random mutations almost never get right, so
// each input is read twice: as given (the checksum and framing paths), then with every
// checksum the framing reaches recomputed (the record decoding behind them).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "engine/input_error.h"
#include "fuzz_check.h"
#include "recording/recording_format.h"
#include "recording/recording_reader.h"

namespace {

using serosa::fuzz::require;
namespace rec = serosa::recording;

std::uint32_t get_u32(const std::vector<std::uint8_t>& b, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v |= std::uint32_t{b[at + i]} << (8 * i);
  return v;
}

void set_u32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (std::size_t i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}

// Recomputes the header's and each well-framed chunk's CRC-32 in place (recording_format.h).
void fix_checksums(std::vector<std::uint8_t>& b) {
  if (b.size() < 12) return;
  const std::size_t hlen = get_u32(b, 8);
  if (hlen > b.size() - 12 || b.size() - 12 - hlen < 4) return;
  set_u32(b, 12 + hlen, rec::crc32(std::span(b.data() + 12, hlen)));
  std::size_t pos = 12 + hlen + 4;
  while (b.size() - pos >= 12 && std::equal(rec::kChunkMagic, rec::kChunkMagic + 4,
                                            b.begin() + static_cast<std::ptrdiff_t>(pos))) {
    const std::size_t len = get_u32(b, pos + 4);
    if (len > b.size() - pos - 12) return;
    set_u32(b, pos + 8, rec::crc32(std::span(b.data() + pos + 12, len)));
    pos += 12 + len;
  }
}

void read(const std::vector<std::uint8_t>& bytes) {
  try {
    const rec::Recording r = rec::parse_recording(bytes, "fuzz.lapr");
    require(r.version >= rec::kOldestVersion && r.version <= rec::kVersion, "version checked");
    require(r.stopped_at <= bytes.size(), "stopped within the file");
    require(r.complete == r.stopped.empty(), "complete exactly when nothing stopped the read");
    require(r.complete || r.stopped.find("at byte ") != std::string::npos,
            "a stop names its byte offset");
    require(!r.corrupt || !r.complete, "corrupt is not complete");
    require(r.chunks >= 0, "chunk count");
  } catch (const serosa::InputError& e) {
    require(e.file() == "fuzz.lapr" && e.line() == 0, "error names the file");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> bytes(data, data + size);
  read(bytes);
  fix_checksums(bytes);
  read(bytes);
  return 0;
}
