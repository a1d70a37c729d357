// Face keys and outward face orientation shared by the Thrust extraction (host and device), the
// incremental update and the tests.
//
// A face is keyed by its three node ids sorted ascending (a < b < c for a valid tet), so the two
// tets sharing a face produce equal keys whatever their node order. Two packings:
//  - NarrowKey (std::uint64_t): a << 42 | b << 21 | c. Exact when every id < 2^21 (2,097,152
//    nodes); a plain integer key, so Thrust's CUDA backend sorts it with a radix sort.
//  - WideKey {hi = a << 31 | b, lo = c}: exact for every non-negative int32 id (< 2^31 nodes),
//    compared lexicographically (hi, lo); CUDA sorts it with a merge sort.
// Both order faces by (a, b, c). The extraction picks NarrowKey when num_nodes <= 2^21.
#pragma once

#include <cstdint>
#include <type_traits>

#include "surface/hd.h"

namespace serosa::surface {

using NarrowKey = std::uint64_t;
inline constexpr std::int64_t kNarrowKeyMaxNodes = std::int64_t{1} << 21;

struct WideKey {
  std::uint64_t hi = 0;  ///< a << 31 | b
  std::uint32_t lo = 0;  ///< c
};
SEROSA_HD inline bool operator==(const WideKey& p, const WideKey& q) {
  return p.hi == q.hi && p.lo == q.lo;
}
SEROSA_HD inline bool operator!=(const WideKey& p, const WideKey& q) { return !(p == q); }
SEROSA_HD inline bool operator<(const WideKey& p, const WideKey& q) {
  return p.hi < q.hi || (p.hi == q.hi && p.lo < q.lo);
}

/// Sorts three ids ascending in place.
SEROSA_HD inline void sort3(std::int32_t& a, std::int32_t& b, std::int32_t& c) {
  std::int32_t t = 0;
  if (b < a) {
    t = a;
    a = b;
    b = t;
  }
  if (c < b) {
    t = b;
    b = c;
    c = t;
  }
  if (b < a) {
    t = a;
    a = b;
    b = t;
  }
}

/// Packs three node ids into a key of type Key (NarrowKey or WideKey); the ids need not be
/// sorted. Ids must be >= 0 (and < 2^21 for NarrowKey).
template <class Key>
SEROSA_HD inline Key make_face_key(std::int32_t a, std::int32_t b, std::int32_t c) {
  sort3(a, b, c);
  const auto ua = static_cast<std::uint64_t>(a);
  const auto ub = static_cast<std::uint64_t>(b);
  const auto uc = static_cast<std::uint32_t>(c);
  if constexpr (std::is_same_v<Key, NarrowKey>) {
    return static_cast<Key>(ua << 42 | ub << 21 | uc);
  } else {
    return Key{ua << 31 | ub, uc};
  }
}

/// The face of tet `t` (anything indexable by 0..3) opposite its local node `l` (0..3), written
/// to (a, b, c) counter-clockwise seen from outside: the normal (b - a) x (c - a) points away
/// from node l when the tet is positively oriented (signed_volume > 0). Local orders:
/// l = 0: (1,2,3); 1: (0,3,2); 2: (0,1,3); 3: (0,2,1). This is engine's kTetFaces
/// (engine/tet_faces.h) written for device code, which cannot include that Eigen header; a test
/// (ExtractSurface.OutwardFaceIsEnginesFaceTable) keeps the two equal.
template <class TetT>
SEROSA_HD inline void outward_face(const TetT& t, int l, std::int32_t& a, std::int32_t& b,
                                   std::int32_t& c) {
  switch (l) {
    case 0:
      a = t[1];
      b = t[2];
      c = t[3];
      break;
    case 1:
      a = t[0];
      b = t[3];
      c = t[2];
      break;
    case 2:
      a = t[0];
      b = t[1];
      c = t[3];
      break;
    default:
      a = t[0];
      b = t[2];
      c = t[1];
      break;
  }
}

}  // namespace serosa::surface
