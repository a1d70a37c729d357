// Prisms and pyramids into tets (paper Tables 1, 2 and Figure 9): for every order of node ids
// (720 for a prism, 120 for a pyramid) the tets fill the primitive exactly with positive volumes
// and cut every quad by its diagonal through the smallest id, so neighbours conform.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "cutting/subdivide.h"
#include "engine/math.h"

namespace serosa::cutting {
namespace {

using Face = std::array<int, 3>;

Face key(int a, int b, int c) {
  Face f{a, b, c};
  std::sort(f.begin(), f.end());
  return f;
}

// Boundary faces (local indices) of a set of tets: faces used once.
std::set<Face> boundary(std::span<const LocalTet> tets) {
  std::map<Face, int> n;
  for (const LocalTet& t : tets)
    for (int s = 0; s < 4; ++s) {
      std::array<int, 3> f{};
      int k = 0;
      for (int j = 0; j < 4; ++j)
        if (j != s) f[k++] = t[j];
      ++n[key(f[0], f[1], f[2])];
    }
  std::set<Face> b;
  for (const auto& [f, c] : n) {
    EXPECT_LE(c, 2);
    if (c == 1) b.insert(f);
  }
  return b;
}

// Expected boundary: triangles as they are, each quad (cyclic a,b,c,d) split by the diagonal
// through its smallest id.
void add_quad(std::set<Face>& out, const std::vector<int>& ids, int a, int b, int c, int d) {
  const int m = std::min({ids[a], ids[b], ids[c], ids[d]});
  if (m == ids[a] || m == ids[c]) {
    out.insert(key(a, b, c));
    out.insert(key(a, c, d));
  } else {
    out.insert(key(a, b, d));
    out.insert(key(b, c, d));
  }
}

double volume(const std::vector<Vec3>& p, const LocalTet& t) {
  return std::abs(signed_volume(p[t[0]], p[t[1]], p[t[2]], p[t[3]]));
}

// Two prisms as they arise from a plane cutting a tet (planar quads): phi at a, b, c, d gives
// the cut points; a frustum (+,-,-,-) and a wedge (+,+,-,-).
std::vector<std::vector<Vec3>> prism_shapes() {
  const std::array<Vec3, 4> x{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.2, 1, 0), Vec3(0.3, 0.3, 1.2)};
  std::vector<std::vector<Vec3>> shapes;
  for (const std::array<double, 4>& phi : {std::array<double, 4>{1.0, -0.4, -1.5, -0.8},
                                           std::array<double, 4>{1.0, 0.5, -0.7, -1.3}}) {
    auto e = [&](int i, int j) { return Vec3(x[i] + phi[i] / (phi[i] - phi[j]) * (x[j] - x[i])); };
    if (phi[1] < 0)
      shapes.push_back({x[1], x[2], x[3], e(0, 1), e(0, 2), e(0, 3)});
    else
      shapes.push_back({x[0], e(0, 2), e(0, 3), x[1], e(1, 2), e(1, 3)});
  }
  return shapes;
}

TEST(Subdivide, EveryPrismOrderFillsAndConforms) {
  for (const auto& shape : prism_shapes()) {
    std::vector<Vec3> pts = shape;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : shape) mean += p / 6.0;
    pts.push_back(mean);
    std::vector<int> ids(6);
    std::iota(ids.begin(), ids.end(), 0);
    int steiner_cases = 0, orders = 0;
    double ref = -1.0;
    do {
      ++orders;
      const PrimitiveSplit s = split_prism({ids[0], ids[1], ids[2], ids[3], ids[4], ids[5]});
      ASSERT_EQ(s.tets.size(), s.steiner ? 8u : 3u);
      steiner_cases += s.steiner ? 1 : 0;
      double v = 0.0;
      for (const LocalTet& t : s.tets) {
        const double vt = volume(pts, t);
        EXPECT_GT(vt, 1e-6);
        v += vt;
      }
      if (ref < 0.0) ref = v;
      EXPECT_NEAR(v, ref, 1e-12);
      std::set<Face> want{key(0, 1, 2), key(3, 4, 5)};
      add_quad(want, ids, 0, 1, 4, 3);
      add_quad(want, ids, 1, 2, 5, 4);
      add_quad(want, ids, 2, 0, 3, 5);
      EXPECT_EQ(boundary(s.tets), want);
    } while (std::next_permutation(ids.begin(), ids.end()));
    EXPECT_EQ(orders, 720);
    // Distinct ids never select a Schönhardt row (see prism_case).
    EXPECT_EQ(steiner_cases, 0);
    // Every row of Table 1, the Steiner rows included, fills the prism.
    for (int row = 0; row < 8; ++row) {
      double v = 0.0;
      for (const LocalTet& t : prism_case(row).tets) {
        EXPECT_GT(volume(pts, t), 1e-6) << row;
        v += volume(pts, t);
      }
      EXPECT_NEAR(v, ref, 1e-12) << row;
    }
    // Volume equals the sum of three tets of a direct decomposition.
    const double direct =
        volume(pts, {0, 1, 2, 3}) + volume(pts, {1, 2, 3, 4}) + volume(pts, {2, 3, 4, 5});
    EXPECT_NEAR(ref, direct, 1e-12);
  }
}

TEST(Subdivide, EveryPyramidOrderFillsAndConforms) {
  const std::vector<Vec3> pts{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1.2, 0.9, 0), Vec3(-0.1, 1, 0),
                              Vec3(0.4, 0.3, 1)};
  std::vector<int> ids(5);
  std::iota(ids.begin(), ids.end(), 0);
  int orders = 0;
  const double total = volume(pts, {0, 1, 2, 4}) + volume(pts, {0, 2, 3, 4});
  do {
    ++orders;
    const PrimitiveSplit s = split_pyramid({ids[0], ids[1], ids[2], ids[3], ids[4]});
    ASSERT_EQ(s.tets.size(), 2u);
    double v = 0.0;
    for (const LocalTet& t : s.tets) {
      EXPECT_GT(volume(pts, t), 1e-6);
      v += volume(pts, t);
    }
    EXPECT_NEAR(v, total, 1e-12);
    std::set<Face> want{key(0, 1, 4), key(1, 2, 4), key(2, 3, 4), key(3, 0, 4)};
    add_quad(want, ids, 0, 1, 2, 3);
    EXPECT_EQ(boundary(s.tets), want);
  } while (std::next_permutation(ids.begin(), ids.end()));
  EXPECT_EQ(orders, 120);
}

}  // namespace
}  // namespace serosa::cutting
