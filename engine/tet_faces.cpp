#include "engine/tet_faces.h"

#include <algorithm>
#include <tuple>

namespace serosa {

namespace {

// Sorts three ids ascending and returns the parity (0 even, 1 odd) of the sorting permutation.
std::uint8_t sort3(Tri& f) {
  std::uint8_t swaps = 0;
  if (f[0] > f[1]) std::swap(f[0], f[1]), ++swaps;
  if (f[1] > f[2]) std::swap(f[1], f[2]), ++swaps;
  if (f[0] > f[1]) std::swap(f[0], f[1]), ++swaps;
  return static_cast<std::uint8_t>(swaps & 1U);
}

}  // namespace

std::vector<TetFace> sorted_tet_faces(std::span<const Tet> tets) {
  std::vector<TetFace> faces;
  faces.reserve(tets.size() * 4);
  for (std::size_t i = 0; i < tets.size(); ++i) {
    for (int k = 0; k < 4; ++k) {
      TetFace f;
      f.key = tet_face(tets[i], k);
      f.parity = sort3(f.key);
      f.tet = static_cast<std::int32_t>(i);
      f.local = static_cast<std::uint8_t>(k);
      faces.push_back(f);
    }
  }
  std::sort(faces.begin(), faces.end(), [](const TetFace& a, const TetFace& b) {
    return std::tie(a.key, a.tet, a.local) < std::tie(b.key, b.tet, b.local);
  });
  return faces;
}

}  // namespace serosa
