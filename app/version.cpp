#include "app/version.h"

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <vector>

#include "engine/fnv1a.h"

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
  Fnv1a f;
  std::vector<char> buf(1 << 16);
  while (in.read(buf.data(), static_cast<std::streamsize>(buf.size())) || in.gcount() > 0) {
    f.bytes(buf.data(), static_cast<std::size_t>(in.gcount()));
    if (!in) break;
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
  return hex;
}

}  // namespace serosa::app
