// The 81-case table: each tet's four node signs (+, 0, - against the cut plane) mapped to one of
// the paper's seven canonical cases (plus "untouched" and "degenerate") by an even permutation of
// its nodes and an optional mirror (+ and - swapped).
#pragma once

#include <array>
#include <cstdint>

namespace serosa::cutting {

/// Side of a node against the cut plane, within the classification tolerance.
enum class Sign : std::int8_t { kNeg = -1, kZero = 0, kPos = 1 };

/// The canonical cases, named by their canonical sign vectors (node 0..3 in canonical order).
/// The paper's seven are kOneThree .. kThreeZero.
enum class CanonicalCase : std::uint8_t {
  kUntouched = 0,  ///< (+,+,+,+): all on one side
  kOneThree,       ///< (+,-,-,-): one node on one side, three on the other
  kTwoTwo,         ///< (+,+,-,-): two on each side
  kOneZeroSplit,   ///< (0,+,-,-): one on the plane, the others on each side
  kOneZeroSame,    ///< (0,+,+,+): one on the plane, the others on the same side
  kTwoZeroSplit,   ///< (0,0,+,-): two on the plane, the others on each side
  kTwoZeroSame,    ///< (0,0,+,+): two on the plane (an edge), the others on the same side
  kThreeZero,      ///< (0,0,0,+): three on the plane (a face)
  kDegenerate,     ///< (0,0,0,0): a flat tet; never cut
};
inline constexpr int kNumCanonicalCases = 9;

/// One row of the table.
struct CaseEntry {
  CanonicalCase canonical = CanonicalCase::kUntouched;
  /// True when the tet matches the canonical signs only after swapping + and -.
  bool mirrored = false;
  /// perm[k] = the tet's local node (0..3) that plays canonical node k. Always an even
  /// permutation, so (t[perm[0]], .., t[perm[3]]) keeps the tet's positive orientation.
  std::array<std::uint8_t, 4> perm{0, 1, 2, 3};
};

/// Case code of four signs: sum over k of (sign_k + 1) * 3^k, in 0..80.
[[nodiscard]] constexpr int case_code(const std::array<Sign, 4>& s) {
  int code = 0;
  for (int k = 3; k >= 0; --k) code = code * 3 + (static_cast<int>(s[k]) + 1);
  return code;
}

/// Inverse of case_code.
[[nodiscard]] constexpr std::array<Sign, 4> signs_of_code(int code) {
  std::array<Sign, 4> s{};
  for (int k = 0; k < 4; ++k) {
    s[k] = static_cast<Sign>(code % 3 - 1);
    code /= 3;
  }
  return s;
}

/// Canonical sign vector of a case (before any mirror).
[[nodiscard]] std::array<Sign, 4> canonical_signs(CanonicalCase c);

/// The 81-entry table, indexed by case_code. A constant built at compile time.
[[nodiscard]] const std::array<CaseEntry, 81>& case_table();

/// Parity of a permutation of 0..3: true when even.
[[nodiscard]] bool is_even_permutation(const std::array<std::uint8_t, 4>& p);

}  // namespace serosa::cutting
