// 64-bit FNV-1a: the one hash behind the state hash, the binary's id and a batch run's
// fingerprint. Stable across builds and machines (unlike std::hash), not cryptographic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace serosa {

struct Fnv1a {
  std::uint64_t h = 0xcbf29ce484222325ull;  ///< the offset basis, or a caller's own
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= c[i];
      h *= 1099511628211ull;
    }
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    const std::uint64_t n = v.size();
    bytes(&n, sizeof n);
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
  /// Length first, so "ab" + "c" and "a" + "bc" differ.
  void text(std::string_view s) {
    const std::uint64_t n = s.size();
    bytes(&n, sizeof n);
    bytes(s.data(), s.size());
  }
  /// A file's bytes, as text() (a file that cannot be read counts as empty).
  void file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream all;
    if (in) all << in.rdbuf();
    text(all.str());
  }
};

}  // namespace serosa
