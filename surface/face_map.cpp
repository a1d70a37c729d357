#include "surface/face_map.h"

#include <utility>

namespace serosa::surface {
namespace {

// Smallest power of two holding n entries at most 70% full (at least 16 slots).
std::size_t capacity_for(std::size_t n) {
  std::size_t c = 16;
  while (c * 7 < n * 10) c *= 2;
  return c;
}

}  // namespace

std::size_t FaceMap::locate(const WideKey& k) const {
  std::size_t i = home(k);
  while (slots_[i].key.hi != kEmptyHi && slots_[i].key != k) i = (i + 1) & mask_;
  return i;
}

void FaceMap::rehash(std::size_t capacity) {
  std::vector<Slot> old = std::move(slots_);
  slots_.assign(capacity, Slot{});
  mask_ = capacity - 1;
  for (const Slot& s : old)
    if (s.key.hi != kEmptyHi) slots_[locate(s.key)] = s;
}

void FaceMap::reserve(std::size_t n) {
  const std::size_t c = capacity_for(n);
  if (c > slots_.size()) rehash(c);
}

FaceEntry* FaceMap::find(const WideKey& k) {
  if (slots_.empty()) return nullptr;
  Slot& s = slots_[locate(k)];
  return s.key.hi == kEmptyHi ? nullptr : &s.value;
}

const FaceEntry* FaceMap::find(const WideKey& k) const {
  if (slots_.empty()) return nullptr;
  const Slot& s = slots_[locate(k)];
  return s.key.hi == kEmptyHi ? nullptr : &s.value;
}

FaceEntry& FaceMap::get_or_insert(const WideKey& k) {
  if ((size_ + 1) * 10 > slots_.size() * 7) rehash(capacity_for(size_ + 1));
  Slot& s = slots_[locate(k)];
  if (s.key.hi == kEmptyHi) {
    s.key = k;
    s.value = FaceEntry{};
    ++size_;
  }
  return s.value;
}

bool FaceMap::erase(const WideKey& k) {
  if (slots_.empty()) return false;
  std::size_t i = locate(k);
  if (slots_[i].key.hi == kEmptyHi) return false;
  // Backward-shift deletion: pull later members of the probe run into the hole when their home
  // does not lie cyclically in (hole, j].
  for (std::size_t j = (i + 1) & mask_; slots_[j].key.hi != kEmptyHi; j = (j + 1) & mask_) {
    const std::size_t h = home(slots_[j].key);
    const bool stays = i <= j ? (i < h && h <= j) : (i < h || h <= j);
    if (!stays) {
      slots_[i] = slots_[j];
      i = j;
    }
  }
  slots_[i] = Slot{};
  --size_;
  return true;
}

}  // namespace serosa::surface
