// Number formatting and file output for the mesh writers (private to engine/io). Doubles are
// written with std::to_chars in their shortest form that reads back to the same double (never
// longer than max_digits10 significant digits), so every write/read round trip is exact.
#pragma once

#include <charconv>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace serosa::io {

inline void append_double(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

inline void append_int(std::string& out, std::int64_t v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// Writes `text` to `path` (replacing it); std::runtime_error naming the file on failure.
void write_text_file(const std::filesystem::path& path, std::string_view text);

}  // namespace serosa::io
