#include "cutting/patterns.h"

namespace serosa::cutting {
namespace {

using K = PrimitiveKind;
using S = Side;

constexpr std::uint8_t e(int i, int j) { return edge_label(i, j); }

// The whole tet on the positive side (untouched, or one-sided with coplanar nodes: the paper's
// "clipping" cases, where only coplanar nodes inside the polygon are cloned).
constexpr std::array<PatternPrimitive, 1> kWhole{{{K::kTet, S::kPos, {0, 1, 2, 3}}}};

// (+,-,-,-): a tet cut off the positive node, a prism on the negative side.
constexpr std::array<PatternPrimitive, 2> kOneThree{{
    {K::kTet, S::kPos, {0, e(0, 1), e(0, 2), e(0, 3)}},
    {K::kPrism, S::kNeg, {1, 2, 3, e(0, 1), e(0, 2), e(0, 3)}},
}};

// (+,+,-,-): a prism on each side; the cut section is the quad e02-e03-e13-e12.
constexpr std::array<PatternPrimitive, 2> kTwoTwo{{
    {K::kPrism, S::kPos, {0, e(0, 2), e(0, 3), 1, e(1, 2), e(1, 3)}},
    {K::kPrism, S::kNeg, {2, e(0, 2), e(1, 2), 3, e(0, 3), e(1, 3)}},
}};

// (0,+,-,-): a tet on the positive side, a pyramid with apex at the coplanar node on the other.
constexpr std::array<PatternPrimitive, 2> kOneZeroSplit{{
    {K::kTet, S::kPos, {0, 1, e(1, 2), e(1, 3)}},
    {K::kPyramid, S::kNeg, {2, 3, e(1, 3), e(1, 2), 0}},
}};

// (0,0,+,-): the tet is split in two through the coplanar edge and the cut point.
constexpr std::array<PatternPrimitive, 2> kTwoZeroSplit{{
    {K::kTet, S::kPos, {0, 1, 2, e(2, 3)}},
    {K::kTet, S::kNeg, {0, 1, e(2, 3), 3}},
}};

}  // namespace

std::span<const PatternPrimitive> pattern(CanonicalCase c) {
  switch (c) {
    case CanonicalCase::kOneThree:
      return kOneThree;
    case CanonicalCase::kTwoTwo:
      return kTwoTwo;
    case CanonicalCase::kOneZeroSplit:
      return kOneZeroSplit;
    case CanonicalCase::kTwoZeroSplit:
      return kTwoZeroSplit;
    case CanonicalCase::kDegenerate:
      return {};
    case CanonicalCase::kUntouched:
    case CanonicalCase::kOneZeroSame:
    case CanonicalCase::kTwoZeroSame:
    case CanonicalCase::kThreeZero:
      return kWhole;
  }
  return {};
}

}  // namespace serosa::cutting
