// Splitting the paper's subdivision primitives, prisms and pyramids, into tets (paper Tables 1
// and 2, Figure 9). The quad faces are cut by the diagonal through the smallest node id of the
// quad, a rule that depends only on the quad's ids, so two primitives sharing a quad agree.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace serosa::cutting {

/// Node layout of a prism: triangles (0,1,2) and (3,4,5), lateral edges 0-3, 1-4, 2-5, so the
/// quads are (0,1,4,3), (1,2,5,4) and (2,0,3,5).
/// Node layout of a pyramid: quad base (0,1,2,3) in cyclic order, apex 4.
using LocalTet = std::array<std::uint8_t, 4>;

/// Tets of a split, as indices into the primitive's nodes. For a prism, index 6 is the Steiner
/// point (the mean of the six nodes), needed only by the two Schönhardt cases (steiner = true).
/// Orientation is not normalised: callers orient each tet.
struct PrimitiveSplit {
  std::span<const LocalTet> tets;
  bool steiner = false;
  int case_index = 0;  ///< row of the paper's table (prism 0..7, pyramid 0..1)
};

/// Paper Figure 9, splitPrism: case bits from the three quads' smallest ids, then Table 1.
/// @param ids (6) global node ids of the prism's nodes, all distinct
[[nodiscard]] PrimitiveSplit split_prism(const std::array<std::int32_t, 6>& ids);

/// Row `case_index` (0..7) of Table 1 (rows 0 and 7 use the Steiner point 6). With distinct
/// ids split_prism never selects rows 0 or 7: the smallest id of the prism lies on two quads and
/// both their diagonals go through it, so the three diagonals can never turn the same way.
[[nodiscard]] PrimitiveSplit prism_case(int case_index);

/// Paper Figure 9, splitPyramid: the base diagonal through the smallest id, then Table 2.
/// @param ids (5) global node ids of the pyramid's nodes, all distinct
[[nodiscard]] PrimitiveSplit split_pyramid(const std::array<std::int32_t, 5>& ids);

/// Triangles of a tet face (a, b, c) whose edges may carry a split point: labels 0, 1, 2 are
/// a, b, c and 3, 4, 5 the points on (a,b), (b,c), (c,a). At most two points (a plane crosses
/// at most two edges of a triangle). One point: joined to the opposite vertex. Two points: the
/// corner triangle at their shared vertex and a quad cut by its diagonal through its smallest
/// id, the same rule as split_prism and split_pyramid, so a face split here matches a face of a
/// neighbouring prism or pyramid.
struct FaceSplit {
  std::array<std::array<std::uint8_t, 3>, 3> tris{};
  int count = 0;
};
/// @param ids (6) global ids of a, b, c and of the points (-1 where an edge has none)
[[nodiscard]] FaceSplit split_face(const std::array<std::int32_t, 6>& ids);

}  // namespace serosa::cutting
