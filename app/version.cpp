#include "app/version.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

namespace serosa::app {

std::string_view version_string() noexcept {
#if defined(SEROSA_HAVE_CUDA)
  return "serosa 0.1.0 (CUDA on)";
#else
  return "serosa 0.1.0 (CUDA off)";
#endif
}

std::string binary_id() {
  std::ifstream in("/proc/self/exe", std::ios::binary);
  if (!in) return "unknown";
  std::uint64_t h = 0xcbf29ce484222325ull;
  std::vector<char> buf(1 << 16);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[static_cast<std::size_t>(i)]);
      h *= 0x100000001b3ull;
    }
    if (!in) break;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

}  // namespace serosa::app
