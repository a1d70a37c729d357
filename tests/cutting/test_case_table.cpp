// The 81-case table: every code maps to the canonical case with the same counts of +, 0 and -,
// through an even permutation (orientation preserved), and the mapped signs are the canonical ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "cutting/case_table.h"
#include "cutting/patterns.h"

namespace serosa::cutting {
namespace {

TEST(CaseTable, CodesRoundTrip) {
  for (int code = 0; code < 81; ++code) EXPECT_EQ(case_code(signs_of_code(code)), code);
}

TEST(CaseTable, EveryCaseMapsToItsCanonicalCase) {
  std::set<CanonicalCase> seen;
  for (int code = 0; code < 81; ++code) {
    const std::array<Sign, 4> s = signs_of_code(code);
    const CaseEntry& e = case_table()[code];
    seen.insert(e.canonical);
    // A permutation of 0..3, and even.
    std::array<std::uint8_t, 4> sorted = e.perm;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, (std::array<std::uint8_t, 4>{0, 1, 2, 3})) << code;
    EXPECT_TRUE(is_even_permutation(e.perm)) << code;
    // Permuted (and mirrored) signs are exactly the canonical signs.
    const std::array<Sign, 4> c = canonical_signs(e.canonical);
    for (int k = 0; k < 4; ++k)
      EXPECT_EQ(static_cast<int>(s[e.perm[k]]) * (e.mirrored ? -1 : 1), static_cast<int>(c[k]))
          << "code " << code << " node " << k;
    // Counts: zeros equal; + and - equal, or swapped when mirrored.
    auto count = [](const std::array<Sign, 4>& v, Sign x) {
      return std::count(v.begin(), v.end(), x);
    };
    EXPECT_EQ(count(s, Sign::kZero), count(c, Sign::kZero));
    EXPECT_EQ(count(s, e.mirrored ? Sign::kNeg : Sign::kPos), count(c, Sign::kPos));
    EXPECT_EQ(count(s, e.mirrored ? Sign::kPos : Sign::kNeg), count(c, Sign::kNeg));
  }
  EXPECT_EQ(seen.size(), static_cast<std::size_t>(kNumCanonicalCases));
}

TEST(CaseTable, CaseCountsMatchCombinatorics) {
  // Number of codes per canonical case: choose which nodes take which sign (x2 when mirrored
  // differs from the original).
  std::array<int, kNumCanonicalCases> n{};
  for (int code = 0; code < 81; ++code) ++n[static_cast<int>(case_table()[code].canonical)];
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kUntouched)], 2);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kOneThree)], 8);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kTwoTwo)], 6);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kOneZeroSplit)], 24);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kOneZeroSame)], 8);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kTwoZeroSplit)], 12);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kTwoZeroSame)], 12);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kThreeZero)], 8);
  EXPECT_EQ(n[static_cast<int>(CanonicalCase::kDegenerate)], 1);
}

TEST(Patterns, UseOnlyCutEdgesOfTheirCase) {
  // A pattern may place a point on canonical edge (i, j) only if its canonical signs are + and -.
  for (int c = 0; c < kNumCanonicalCases; ++c) {
    const auto sg = canonical_signs(static_cast<CanonicalCase>(c));
    for (const PatternPrimitive& p : pattern(static_cast<CanonicalCase>(c)))
      for (int k = 0; k < p.size(); ++k) {
        const std::uint8_t l = p.points[k];
        ASSERT_LT(l, 10);
        if (!is_edge_label(l)) {
          // A node's own side: never a node strictly on the other side.
          const int want = p.side == Side::kPos ? 1 : -1;
          EXPECT_NE(static_cast<int>(sg[l]), -want) << "case " << c;
          continue;
        }
        const auto& e = kEdgeNodes[l - 4];
        EXPECT_LT(static_cast<int>(sg[e[0]]) * static_cast<int>(sg[e[1]]), 0) << "case " << c;
      }
  }
}

}  // namespace
}  // namespace serosa::cutting
