// The trainee's depth cue and the active instrument's collar (render/tool_mesh.h): the ring lies
// on the tissue's tangent plane round the point nearest the tip, closes in with the distance and
// turns amber at contact, over random poses; nothing beyond range or without a tissue point; the
// collar only on the active instrument; and in a picture the ring shows on the surface.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "render/picture_test.h"
#include "render/render_fixtures.h"
#include "render/tool_mesh.h"

namespace serosa::render {
namespace {

constexpr std::array<float, 3> kAmber{1.0f, 0.85f, 0.10f};
constexpr std::array<float, 3> kCollarGreen{0.20f, 0.95f, 0.35f};

bool has_colour(const ToolMesh& m, std::size_t v, const std::array<float, 3>& c) {
  return std::abs(m.material[4 * v] - c[0]) < 1e-6f &&
         std::abs(m.material[4 * v + 1] - c[1]) < 1e-6f &&
         std::abs(m.material[4 * v + 2] - c[2]) < 1e-6f;
}

TEST(DepthCue, ARingOnTheTangentPlaneThatClosesInAndLightsUpAtContact) {
  std::mt19937 rng(3);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::uniform_real_distribution<float> d(-0.002f, 0.06f);
  int drawn = 0, touching = 0;
  for (int i = 0; i < 2000; ++i) {
    RenderTool t;
    t.has_tissue = true;
    const Eigen::Vector3f p(g(rng), g(rng), g(rng));
    const Eigen::Vector3f n = Eigen::Vector3f(g(rng), g(rng), g(rng)).normalized();
    t.tissue_point = {p.x(), p.y(), p.z()};
    t.tissue_normal = {n.x(), n.y(), n.z()};
    t.tissue_distance_m = d(rng);
    ToolMesh m;
    append_depth_cue(t, m);
    if (!(t.tissue_distance_m < kDepthCueRange)) {
      ASSERT_EQ(m.num_vertices(), 0u) << i;
      continue;
    }
    ASSERT_GT(m.num_triangles(), 0u) << i;
    ++drawn;
    const bool touch = t.tissue_distance_m <= kTouchDistance;
    touching += touch ? 1 : 0;
    const float outer = kDepthCueMinRadius + kDepthCueSpread * std::max(t.tissue_distance_m, 0.0f);
    float largest = 0.0f;
    for (std::size_t v = 0; v < m.num_vertices(); ++v) {
      const Eigen::Vector3f q(m.pos[3 * v], m.pos[3 * v + 1], m.pos[3 * v + 2]);
      ASSERT_NEAR((q - p).dot(n), kDepthCueLift, 1e-5f) << i;  // on the lifted tangent plane
      largest = std::max(largest, (q - p).norm());
      ASSERT_EQ(has_colour(m, v, kAmber), touch) << i;
    }
    ASSERT_NEAR(largest, outer, 1e-5f) << i;
    for (const std::uint32_t id : m.tri) ASSERT_LT(id, m.num_vertices());
  }
  EXPECT_GT(drawn, 1000);
  EXPECT_GT(touching, 10);
  RenderTool none;
  none.tissue_distance_m = 0.01f;  // no tissue point known
  ToolMesh m;
  append_depth_cue(none, m);
  EXPECT_EQ(m.num_vertices(), 0u);
}

TEST(DepthCue, TheCollarMarksOnlyTheActiveInstrument) {
  for (const bool active : {false, true}) {
    for (const auto kind : {RenderTool::Kind::kGrasper, RenderTool::Kind::kScissors,
                            RenderTool::Kind::kHook, RenderTool::Kind::kEndoloop}) {
      RenderTool t;
      t.kind = kind;
      t.active = active;
      ToolMesh m;
      append_tool_mesh(t, m);
      std::size_t green = 0;
      for (std::size_t v = 0; v < m.num_vertices(); ++v) green += has_colour(m, v, kCollarGreen);
      EXPECT_EQ(green > 0, active);
    }
  }
}

using DepthCuePicture = fixtures::PictureTest;

// A grasper 6 mm above a sphere: the picture with the cue differs from the one without in a ring
// of pixels round the point under the tip, and nowhere far from it.
TEST_F(DepthCuePicture, TheRingShowsOnTheSurfaceUnderTheTip) {
  RenderFrame f = fixtures::frame_of(fixtures::icosphere(4, 0.02f), 1, 0.09f);
  f.group_names = {"", "appendix"};
  RenderTool t;
  t.kind = RenderTool::Kind::kGrasper;
  t.tip = {0.0f, 0.0f, 0.026f};
  t.has_trocar = true;
  t.trocar = {0.06f, 0.0f, 0.08f};
  t.has_tissue = true;
  t.tissue_point = {0.0f, 0.0f, 0.02f};
  t.tissue_normal = {0.0f, 0.0f, 1.0f};
  t.tissue_distance_m = 0.006f;
  f.tools.push_back(t);
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  o.depth_cue = false;
  const Image without = shoot(f, o, "depth_cue_off");
  o.depth_cue = true;
  const Image with = shoot(f, o, "depth_cue_on");
  std::size_t changed = 0, far = 0;
  for (int y = 0; y < with.height; ++y) {
    for (int x = 0; x < with.width; ++x) {
      const std::size_t k =
          4 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(with.width) +
               static_cast<std::size_t>(x));
      const int diff = std::abs(int(with.rgba[k]) - int(without.rgba[k])) +
                       std::abs(int(with.rgba[k + 1]) - int(without.rgba[k + 1])) +
                       std::abs(int(with.rgba[k + 2]) - int(without.rgba[k + 2]));
      if (diff < 30) continue;
      ++changed;
      // The ring's outer radius is 5.4 mm at 7 cm: about 40 pixels round the centre here.
      if (std::hypot(x - 160.0, y - 120.0) > 70.0) ++far;
    }
  }
  EXPECT_GT(changed, 100u);
  EXPECT_EQ(far, 0u);
}

}  // namespace
}  // namespace serosa::render
