#include "cutting/subdivide.h"

#include <algorithm>

namespace serosa::cutting {
namespace {

// Paper Table 1, rows indexed by the case bits of Figure 9. Rows 0 and 7 are the Schönhardt
// prisms (all three diagonals turning the same way) and use the Steiner point 6.
constexpr std::array<LocalTet, 8> kPrism0{{{0, 1, 2, 6},
                                           {0, 1, 3, 6},
                                           {1, 3, 4, 6},
                                           {1, 2, 4, 6},
                                           {2, 4, 5, 6},
                                           {0, 2, 5, 6},
                                           {0, 3, 5, 6},
                                           {3, 4, 5, 6}}};
constexpr std::array<LocalTet, 3> kPrism1{{{0, 1, 3, 5}, {1, 3, 4, 5}, {0, 1, 2, 5}}};
constexpr std::array<LocalTet, 3> kPrism2{{{0, 1, 2, 3}, {1, 2, 3, 4}, {2, 3, 4, 5}}};
constexpr std::array<LocalTet, 3> kPrism3{{{0, 1, 2, 3}, {1, 3, 4, 5}, {1, 2, 3, 5}}};
constexpr std::array<LocalTet, 3> kPrism4{{{0, 3, 4, 5}, {0, 1, 2, 4}, {0, 2, 4, 5}}};
constexpr std::array<LocalTet, 3> kPrism5{{{0, 3, 4, 5}, {0, 1, 4, 5}, {0, 1, 2, 5}}};
constexpr std::array<LocalTet, 3> kPrism6{{{0, 2, 3, 4}, {0, 1, 2, 4}, {2, 3, 4, 5}}};
constexpr std::array<LocalTet, 8> kPrism7{{{0, 1, 2, 6},
                                           {0, 3, 4, 6},
                                           {0, 1, 4, 6},
                                           {1, 4, 5, 6},
                                           {1, 2, 5, 6},
                                           {2, 3, 5, 6},
                                           {0, 2, 3, 6},
                                           {3, 4, 5, 6}}};

// Paper Table 2.
constexpr std::array<LocalTet, 2> kPyramid0{{{0, 1, 2, 4}, {0, 2, 3, 4}}};
constexpr std::array<LocalTet, 2> kPyramid1{{{1, 2, 3, 4}, {0, 1, 3, 4}}};

}  // namespace

PrimitiveSplit prism_case(int c) {
  switch (c) {
    case 0:
      return {kPrism0, true, 0};
    case 1:
      return {kPrism1, false, 1};
    case 2:
      return {kPrism2, false, 2};
    case 3:
      return {kPrism3, false, 3};
    case 4:
      return {kPrism4, false, 4};
    case 5:
      return {kPrism5, false, 5};
    case 6:
      return {kPrism6, false, 6};
    default:
      return {kPrism7, true, 7};
  }
}

PrimitiveSplit split_prism(const std::array<std::int32_t, 6>& n) {
  int c = 0;
  if (std::min(n[1], n[3]) > std::min(n[0], n[4])) c |= 4;  // quad (0,1,4,3): diagonal 0-4
  if (std::min(n[0], n[5]) > std::min(n[2], n[3])) c |= 2;  // quad (2,0,3,5): diagonal 2-3
  if (std::min(n[2], n[4]) > std::min(n[1], n[5])) c |= 1;  // quad (1,2,5,4): diagonal 1-5
  return prism_case(c);
}

PrimitiveSplit split_pyramid(const std::array<std::int32_t, 5>& n) {
  if (std::min(n[0], n[2]) > std::min(n[1], n[3])) return {kPyramid1, false, 1};
  return {kPyramid0, false, 0};
}

FaceSplit split_face(const std::array<std::int32_t, 6>& ids) {
  FaceSplit f;
  const bool ab = ids[3] >= 0, bc = ids[4] >= 0, ca = ids[5] >= 0;
  auto tri = [&f](int x, int y, int z) {
    f.tris[f.count++] = {static_cast<std::uint8_t>(x), static_cast<std::uint8_t>(y),
                         static_cast<std::uint8_t>(z)};
  };
  auto quad = [&](int q0, int q1, int q2, int q3) {  // cyclic; diagonal through the smallest id
    const std::int32_t m = std::min({ids[q0], ids[q1], ids[q2], ids[q3]});
    if (m == ids[q0] || m == ids[q2]) {
      tri(q0, q1, q2);
      tri(q0, q2, q3);
    } else {
      tri(q1, q2, q3);
      tri(q1, q3, q0);
    }
  };
  const int points = (ab ? 1 : 0) + (bc ? 1 : 0) + (ca ? 1 : 0);
  if (points == 0 || points == 3) {  // three is not a plane cut; left whole
    tri(0, 1, 2);
  } else if (points == 1) {
    if (ab) {
      tri(0, 3, 2);
      tri(3, 1, 2);
    } else if (bc) {
      tri(1, 4, 0);
      tri(4, 2, 0);
    } else {
      tri(2, 5, 1);
      tri(5, 0, 1);
    }
  } else if (ab && ca) {
    tri(0, 3, 5);
    quad(3, 1, 2, 5);
  } else if (ab && bc) {
    tri(1, 4, 3);
    quad(4, 2, 0, 3);
  } else {
    tri(2, 5, 4);
    quad(5, 0, 1, 4);
  }
  return f;
}

}  // namespace serosa::cutting
