// reserve_for_cuts and TetBvh's spare capacity: sizes and contents unchanged, capacity for the
// spare, no reallocation when enough is left, clear errors on a bad spare.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "cutting/reserve.h"
#include "cutting/tet_bvh.h"

namespace serosa::cutting {
namespace {

TetMesh two_tets() {
  TetMesh m;
  m.add_node(Vec3(0, 0, 0));
  m.add_node(Vec3(1, 0, 0));
  m.add_node(Vec3(0, 1, 0));
  m.add_node(Vec3(0, 0, 1));
  m.add_node(Vec3(2, 2, 2));
  m.add_tet({0, 1, 2, 3}, 1);
  m.add_tet({1, 2, 3, 4}, 2);
  m.fill_node_state();
  m.tets.shrink_to_fit();
  m.rest.shrink_to_fit();
  return m;
}

TEST(ReserveForCuts, CapacityForTheSpareContentsUnchanged) {
  TetMesh m = two_tets();
  for (int i = 0; i < 98; ++i) m.add_node(Vec3(i, 0, 0));
  m.fill_node_state();
  for (int i = 0; i < 198; ++i) m.add_tet({0, 1, 2, 3}, 3);
  for (auto* v : {&m.rest, &m.x, &m.v}) v->shrink_to_fit();
  m.mass.shrink_to_fit();
  m.fixed.shrink_to_fit();
  m.tets.shrink_to_fit();
  m.group.shrink_to_fit();
  const TetMesh before = m;
  reserve_for_cuts(m, 0.5);
  EXPECT_EQ(m.rest, before.rest);
  EXPECT_EQ(m.x, before.x);
  EXPECT_EQ(m.tets, before.tets);
  EXPECT_EQ(m.group, before.group);
  EXPECT_GE(m.rest.capacity(), 150u);
  EXPECT_GE(m.x.capacity(), 150u);
  EXPECT_GE(m.v.capacity(), 150u);
  EXPECT_GE(m.mass.capacity(), 150u);
  EXPECT_GE(m.fixed.capacity(), 150u);
  EXPECT_GE(m.tets.capacity(), 300u);
  EXPECT_GE(m.group.capacity(), 300u);
  // Enough spare left: a second call reallocates nothing, and appends within it neither.
  const Tet* tets = m.tets.data();
  const Vec3* rest = m.rest.data();
  reserve_for_cuts(m, 0.5);
  for (int i = 0; i < 20; ++i) m.add_tet({0, 1, 2, 3}, 3);
  for (int i = 0; i < 10; ++i) m.add_node(Vec3(0, i, 0));
  reserve_for_cuts(m, 0.5);
  EXPECT_EQ(m.tets.data(), tets);
  EXPECT_EQ(m.rest.data(), rest);
  // Most of the spare used up: reserves again.
  for (int i = 0; i < 60; ++i) m.add_tet({0, 1, 2, 3}, 3);
  const auto size = m.tets.size();
  reserve_for_cuts(m, 0.5);
  EXPECT_GE(static_cast<double>(m.tets.capacity()), 1.5 * static_cast<double>(size));
}

TEST(ReserveForCuts, RejectsABadSpare) {
  TetMesh m = two_tets();
  EXPECT_THROW(reserve_for_cuts(m, -0.1), std::invalid_argument);
  EXPECT_THROW(reserve_for_cuts(m, std::numeric_limits<double>::quiet_NaN()),
               std::invalid_argument);
  EXPECT_THROW(TetBvh(m, -1.0), std::invalid_argument);
  EXPECT_THROW(TetBvh(m, std::numeric_limits<double>::infinity()), std::invalid_argument);
  reserve_for_cuts(m, 0.0);  // no spare asked: fine
  EXPECT_EQ(m.num_tets(), 2);
}

TEST(ReserveForCuts, BvhWithAnySpareFindsTheSameTets) {
  const TetMesh m = two_tets();
  for (double spare : {0.0, 0.5, 3.0}) {
    const TetBvh bvh(m, spare);
    std::vector<std::int32_t> out;
    bvh.query(Vec3(1.5, 1.5, 1.5), Vec3(3, 3, 3), out);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0], 1);
    EXPECT_EQ(bvh.num_tets(), 2);
  }
}

}  // namespace
}  // namespace serosa::cutting
