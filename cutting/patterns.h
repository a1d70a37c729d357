// The subdivision patterns of the canonical cases (complete cuts), as primitives over canonical
// point labels. See docs/cutting.md for the design.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "cutting/case_table.h"

namespace serosa::cutting {

/// Point labels of a pattern: 0..3 are the canonical nodes; 4..9 the cut points on the canonical
/// edges (0,1), (0,2), (0,3), (1,2), (1,3), (2,3) in that order.
inline constexpr std::array<std::array<std::uint8_t, 2>, 6> kEdgeNodes{
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};
[[nodiscard]] constexpr std::uint8_t edge_label(int i, int j) {
  for (std::uint8_t e = 0; e < 6; ++e)
    if ((kEdgeNodes[e][0] == i && kEdgeNodes[e][1] == j) ||
        (kEdgeNodes[e][0] == j && kEdgeNodes[e][1] == i))
      return static_cast<std::uint8_t>(4 + e);
  return 255;
}
[[nodiscard]] constexpr bool is_edge_label(std::uint8_t l) { return l >= 4 && l < 10; }

enum class PrimitiveKind : std::uint8_t { kTet, kPyramid, kPrism };

/// Side of the cut a primitive lies on, in canonical signs (a mirrored case swaps them).
enum class Side : std::uint8_t { kPos, kNeg };

/// One primitive: a tet (4 labels), a pyramid (base quad in cyclic order, then apex) or a prism
/// (triangles 0-1-2 and 3-4-5, lateral edges 0-3, 1-4, 2-5), the layouts of cutting/subdivide.h.
struct PatternPrimitive {
  PrimitiveKind kind = PrimitiveKind::kTet;
  Side side = Side::kPos;
  std::array<std::uint8_t, 6> points{};
  [[nodiscard]] int size() const {
    return kind == PrimitiveKind::kTet ? 4 : kind == PrimitiveKind::kPyramid ? 5 : 6;
  }
};

/// Primitives of a complete cut of the canonical case (empty for kDegenerate). Untouched and
/// one-sided cases are the tet itself on the positive side.
[[nodiscard]] std::span<const PatternPrimitive> pattern(CanonicalCase c);

}  // namespace serosa::cutting
