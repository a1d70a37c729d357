// Phong tessellation on the CPU (the shader's formula): flat at alpha 0, corners kept, crack-free
// edges, planes stay planes, and a coarse sphere gets closer to the true sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/phong_tessellation.h"
#include "render/render_fixtures.h"

namespace serosa::render {
namespace {

using P3 = std::array<float, 3>;

P3 random_p3(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  return {u(rng), u(rng), u(rng)};
}

float dist(const P3& a, const P3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                   (a[2] - b[2]) * (a[2] - b[2]));
}

TEST(PhongTessellation, FlatAtAlphaZeroCornersKeptEdgesCrackFree) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  for (int trial = 0; trial < 500; ++trial) {
    const std::array<P3, 3> p{random_p3(rng), random_p3(rng), random_p3(rng)};
    const std::array<P3, 3> n{random_p3(rng), random_p3(rng), random_p3(rng)};
    const float alpha = u01(rng);
    float b1 = u01(rng), b2 = u01(rng);
    if (b1 + b2 > 1.0f) {
      b1 = 1.0f - b1;
      b2 = 1.0f - b2;
    }
    const P3 b{1.0f - b1 - b2, b1, b2};
    const P3 flat = phong_point(p, n, b, 0.0f);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(flat[k], b[0] * p[0][k] + b[1] * p[1][k] + b[2] * p[2][k], 1e-5f);
    for (int c = 0; c < 3; ++c) {
      P3 bc{0.0f, 0.0f, 0.0f};
      bc[c] = 1.0f;
      EXPECT_LT(dist(phong_point(p, n, bc, alpha), p[c]), 1e-5f);
    }
    // A point on edge p0-p1 ignores the third corner entirely.
    const P3 be{1.0f - b1, b1, 0.0f};
    std::array<P3, 3> p2 = p;
    std::array<P3, 3> n2 = n;
    p2[2] = random_p3(rng);
    n2[2] = random_p3(rng);
    EXPECT_LT(dist(phong_point(p, n, be, alpha), phong_point(p2, n2, be, alpha)), 1e-5f);
  }
}

TEST(PhongTessellation, PlaneStaysPlane) {
  const std::vector<float> pos{0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::vector<float> nrm{0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<std::uint32_t> tri{0, 1, 2};
  const TriMesh m = phong_tessellate(pos, nrm, tri, 5, 0.75f);
  EXPECT_EQ(m.tri.size(), 3u * 25u);
  EXPECT_EQ(m.pos.size(), 3u * 21u);
  for (std::size_t i = 2; i < m.pos.size(); i += 3) EXPECT_NEAR(m.pos[i], 0.0f, 1e-7f);
  EXPECT_THROW((void)phong_tessellate(pos, nrm, tri, 0, 0.5f), std::invalid_argument);
  const std::vector<std::uint32_t> bad{0, 1, 3};
  EXPECT_THROW((void)phong_tessellate(pos, nrm, bad, 2, 0.5f), std::invalid_argument);
}

TEST(PhongTessellation, CoarseSphereApproachesTheSphere) {
  const float r = 1.0f;
  const auto ico = fixtures::icosahedron(r);
  std::vector<float> nrm = ico.pos;  // radial normals (the exact sphere's)
  const SphereDistance flat =
      distance_to_sphere(phong_tessellate(ico.pos, nrm, ico.tri, 1, 0.0f), r);
  const SphereDistance l3 =
      distance_to_sphere(phong_tessellate(ico.pos, nrm, ico.tri, 3, 0.75f), r);
  const SphereDistance l6 =
      distance_to_sphere(phong_tessellate(ico.pos, nrm, ico.tri, 6, 0.75f), r);
  // The icosahedron's faces sit 0.2 r inside the sphere at their centres.
  EXPECT_NEAR(flat.max_m, 1.0 - 0.7947, 0.01);
  EXPECT_LT(l3.max_m, 0.6 * flat.max_m);
  EXPECT_LT(l3.mean_m, 0.5 * flat.mean_m);
  // Finer levels converge to the Phong surface, not to the sphere: no monotone error, but it
  // stays well below the flat error.
  EXPECT_LT(l6.max_m, 0.6 * flat.max_m);
  EXPECT_LT(l6.mean_m, 0.5 * flat.mean_m);
  // Flat tessellation at any level is the input surface.
  const SphereDistance flat6 =
      distance_to_sphere(phong_tessellate(ico.pos, nrm, ico.tri, 6, 0.0f), r);
  EXPECT_NEAR(flat6.max_m, flat.max_m, 1e-4);
}

}  // namespace
}  // namespace serosa::render
