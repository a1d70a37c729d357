#include "cutting/case_table.h"

#include <algorithm>

namespace serosa::cutting {
namespace {

constexpr Sign P = Sign::kPos;
constexpr Sign Z = Sign::kZero;
constexpr Sign N = Sign::kNeg;

// Canonical sign vectors, indexed by CanonicalCase.
constexpr std::array<std::array<Sign, 4>, kNumCanonicalCases> kCanonical{{
    {P, P, P, P},  // kUntouched
    {P, N, N, N},  // kOneThree
    {P, P, N, N},  // kTwoTwo
    {Z, P, N, N},  // kOneZeroSplit
    {Z, P, P, P},  // kOneZeroSame
    {Z, Z, P, N},  // kTwoZeroSplit
    {Z, Z, P, P},  // kTwoZeroSame
    {Z, Z, Z, P},  // kThreeZero
    {Z, Z, Z, Z},  // kDegenerate
}};

constexpr bool even(const std::array<std::uint8_t, 4>& p) {
  int inversions = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) inversions += p[i] > p[j] ? 1 : 0;
  return inversions % 2 == 0;
}

// For each code, the first (case, mirror, even permutation) in a fixed search order that maps
// the tet's signs onto the canonical ones: unmirrored before mirrored, permutations in
// lexicographic order.
constexpr std::array<CaseEntry, 81> build_table() {
  std::array<CaseEntry, 81> table{};
  for (int code = 0; code < 81; ++code) {
    const std::array<Sign, 4> s = signs_of_code(code);
    bool found = false;
    for (int mirror = 0; mirror < 2 && !found; ++mirror) {
      for (int c = 0; c < kNumCanonicalCases && !found; ++c) {
        std::array<std::uint8_t, 4> p{0, 1, 2, 3};
        do {
          if (!even(p)) continue;
          bool match = true;
          for (int k = 0; k < 4; ++k) {
            const int sk = static_cast<int>(s[p[k]]) * (mirror != 0 ? -1 : 1);
            match = match && sk == static_cast<int>(kCanonical[c][k]);
          }
          if (match) {
            table[code] = CaseEntry{static_cast<CanonicalCase>(c), mirror != 0, p};
            found = true;
            break;
          }
        } while (std::next_permutation(p.begin(), p.end()));
      }
    }
  }
  return table;
}

constexpr std::array<CaseEntry, 81> kTable = build_table();

}  // namespace

std::array<Sign, 4> canonical_signs(CanonicalCase c) { return kCanonical[static_cast<int>(c)]; }

const std::array<CaseEntry, 81>& case_table() { return kTable; }

bool is_even_permutation(const std::array<std::uint8_t, 4>& p) { return even(p); }

}  // namespace serosa::cutting
