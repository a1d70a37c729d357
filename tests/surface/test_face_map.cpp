// FaceMap (surface/face_map.h) against std::map over random inserts, updates and erases,
// with keys crowded into few probe runs.
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <tuple>

#include "surface/face_map.h"

namespace serosa::surface {
namespace {

TEST(FaceMap, MatchesStdMap) {
  std::mt19937 rng(8);
  for (int range : {20, 300, 5000}) {  // few distinct keys: long runs, many re-inserts
    FaceMap map;
    std::map<std::tuple<std::uint64_t, std::uint32_t>, std::int32_t> ref;
    std::uniform_int_distribution<std::int32_t> id(0, range);
    for (int step = 0; step < 40000; ++step) {
      const WideKey k = make_face_key<WideKey>(id(rng), id(rng) + range + 1, id(rng));
      const auto rk = std::make_tuple(k.hi, k.lo);
      const unsigned op = rng() % 3;
      if (op == 0) {
        FaceEntry& e = map.get_or_insert(k);
        ++e.count;
        ++ref[rk];
      } else if (op == 1) {
        ASSERT_EQ(map.erase(k), ref.erase(rk) == 1) << "step " << step;
      } else {
        const FaceEntry* e = map.find(k);
        const auto it = ref.find(rk);
        ASSERT_EQ(e != nullptr, it != ref.end()) << "step " << step;
        if (e != nullptr) {
          ASSERT_EQ(e->count, it->second) << "step " << step;
        }
      }
      ASSERT_EQ(map.size(), ref.size());
    }
    // Every key left is found with its count.
    for (const auto& [rk, count] : ref) {
      const FaceEntry* e = map.find(WideKey{std::get<0>(rk), std::get<1>(rk)});
      ASSERT_NE(e, nullptr);
      EXPECT_EQ(e->count, count);
    }
  }
}

TEST(FaceMap, EmptyAndReserve) {
  FaceMap map;
  EXPECT_TRUE(map.empty());
  EXPECT_EQ(map.find(WideKey{1, 2}), nullptr);
  EXPECT_FALSE(map.erase(WideKey{1, 2}));
  map.reserve(1000);
  map.get_or_insert(WideKey{1, 2}).pos = 7;
  EXPECT_EQ(map.find(WideKey{1, 2})->pos, 7);
  EXPECT_EQ(map.size(), 1u);
}

}  // namespace
}  // namespace serosa::surface
