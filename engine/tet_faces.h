// The four faces of a tetrahedron and the sort-by-key face census behind boundary extraction and
// mesh checks (reference CPU code; surface/ has the Thrust version for the running simulation).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/math.h"

namespace serosa {

/// Local node indices of the four faces of a positively oriented tet (a, b, c, d) = (0, 1, 2, 3),
/// each wound counter-clockwise seen from outside, so that its right-hand normal points away from
/// the opposite node. Face k is the one opposite local node k. Derivation: for the unit tet
/// a = 0, b = e1, c = e2, d = e3 (signed volume 1/6 > 0), face (b, c, d) has normal
/// (c - b) x (d - b) = (1, 1, 1), away from a; the other three follow by the same check
/// (tests/engine/test_boundary.cpp verifies all four on random tets).
inline constexpr std::array<std::array<int, 3>, 4> kTetFaces{{
    {1, 2, 3},  // opposite a
    {0, 3, 2},  // opposite b
    {0, 1, 3},  // opposite c
    {0, 2, 1},  // opposite d
}};

/// One face of one tet, keyed by its sorted node ids.
struct TetFace {
  Tri key;                 ///< node ids sorted ascending
  std::int32_t tet = -1;   ///< owning tet
  std::uint8_t local = 0;  ///< face index 0..3 in kTetFaces (opposite local node `local`)
  /// Parity of the permutation taking the outward-wound face to `key`: two tets that share a face
  /// from opposite sides (a consistent mesh) give it opposite parities.
  std::uint8_t parity = 0;
};

/// The outward-wound face `local` of tet `t` (node ids).
[[nodiscard]] inline Tri tet_face(const Tet& t, int local) {
  const auto& f = kTetFaces[static_cast<std::size_t>(local)];
  return {t[static_cast<std::size_t>(f[0])], t[static_cast<std::size_t>(f[1])],
          t[static_cast<std::size_t>(f[2])]};
}

/// All 4m faces of `tets`, sorted by (key, tet, local), so equal keys are adjacent.
/// @param tets (m) node ids per tet; ids are not range-checked (only compared)
/// @return (4m) faces
[[nodiscard]] std::vector<TetFace> sorted_tet_faces(std::span<const Tet> tets);

}  // namespace serosa
