// FaceMap: an open-addressing hash map from face key (WideKey) to the incremental update's
// per-face record, flat in one array (linear probing, backward-shift deletion). It replaced a
// std::unordered_map: one cache miss per lookup instead of two or three, and no allocation per
// insert or erase (the update's cost is mostly these lookups; docs/BENCHMARKS.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "surface/face_key.h"

namespace serosa::surface {

struct WideKeyHash {
  std::size_t operator()(const WideKey& k) const noexcept {
    std::uint64_t z = k.hi * 0x9E3779B97F4A7C15ull ^ (std::uint64_t{k.lo} + 0x632BE59BD9B4E019ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;  // splitmix64 finaliser
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(z ^ (z >> 31));
  }
};

/// What the incremental update knows of one face.
struct FaceEntry {
  std::int32_t count = 0;     ///< tets using the face (1: boundary, 2: interior, 3+: invalid)
  std::int32_t pos = -1;      ///< index in SurfaceMesh::faces, -1 when not there
  std::int64_t code_sum = 0;  ///< sum of 4 tet + l over its uses: the owner when count == 1
};

/// Hash map WideKey -> FaceEntry. Pointers returned by find() stay valid until the next
/// get_or_insert() or erase(). Deterministic: same operations, same layout.
class FaceMap {
 public:
  /// Room for n entries without growing.
  void reserve(std::size_t n);
  /// The entry of k, or null.
  [[nodiscard]] FaceEntry* find(const WideKey& k);
  [[nodiscard]] const FaceEntry* find(const WideKey& k) const;
  /// The entry of k, inserted (default) when absent.
  FaceEntry& get_or_insert(const WideKey& k);
  /// Removes k; false when absent.
  bool erase(const WideKey& k);
  /// Hints the CPU to load k's home slot (no effect on the contents).
  void prefetch(const WideKey& k) const {
    if (!slots_.empty()) __builtin_prefetch(&slots_[home(k)]);
  }
  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] bool empty() const { return size_ == 0; }

 private:
  struct Slot {
    WideKey key{kEmptyHi, 0};
    FaceEntry value;
  };
  // No real key has hi >= 2^62 (a, b < 2^31), so this marks an empty slot.
  static constexpr std::uint64_t kEmptyHi = ~std::uint64_t{0};

  [[nodiscard]] std::size_t home(const WideKey& k) const { return WideKeyHash{}(k)&mask_; }
  [[nodiscard]] std::size_t locate(const WideKey& k) const;  // slot of k, or the empty one
  void rehash(std::size_t capacity);

  std::vector<Slot> slots_;  ///< power-of-two count, at most 70% full
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace serosa::surface
