// The abdomen around the organs: its mesh (geometry, no GL), how it keeps clear of the organs,
// and the pictures through EGL (the view filled around the organs instead of a black void).
// Pictures go to <build>/test-output/render/.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/image_stats.h"
#include "render/picture_test.h"
#include "render/png_writer.h"
#include "render/render_fixtures.h"
#include "render/scenery.h"
#include "render/snapshot.h"

namespace serosa::render {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

V3 v3(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }
V3 vertex(const Scenery& s, std::size_t i) {
  return {s.pos[3 * i], s.pos[3 * i + 1], s.pos[3 * i + 2]};
}

// A 4 cm organ resting on the plane z = 0 (its box, m), the cranial direction +y.
AbdomenPlacement flat_placement() {
  AbdomenPlacement p;
  p.point_m = {0.0f, 0.0f, 0.0f};
  p.normal = {0.0f, 0.0f, 1.0f};
  p.organs_lo_m = {-0.02f, -0.02f, 0.0f};
  p.organs_hi_m = {0.02f, 0.02f, 0.04f};
  p.up_hint = {0.0f, 1.0f, 0.0f};
  return p;
}

// The same organ box over a tilted plane, and over a wall facing +y (a body lying on its side).
std::vector<AbdomenPlacement> placements() {
  std::vector<AbdomenPlacement> out{flat_placement(), flat_placement(), flat_placement()};
  out[1].normal = {0.3f, -0.2f, 1.0f};  // not unit: the generator normalises it
  out[1].point_m = {0.01f, 0.0f, -0.01f};
  out[1].organs_hi_m = {0.07f, 0.03f, 0.05f};  // an elongated organ
  out[2].normal = {0.0f, 1.0f, 0.0f};
  out[2].point_m = {0.0f, -0.02f, 0.0f};
  out[2].up_hint = {0.0f, 1.0f, 0.0f};  // along the normal: the generator picks an axis
  return out;
}

// Convex hull (counter-clockwise) of 2-D points, Andrew's monotone chain.
std::vector<V2> hull(std::vector<V2> pts) {
  std::sort(pts.begin(), pts.end(), [](const V2& a, const V2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  const auto cross = [](const V2& o, const V2& a, const V2& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<V2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross(h[k - 2], h[k - 1], pts[i - 1]) <= 0) --k;
    h[k++] = pts[i - 1];
  }
  h.resize(k - 1);
  return h;
}

// Distance of q from a counter-clockwise convex polygon, 0 inside.
double polygon_distance(const V2& q, const std::vector<V2>& poly) {
  bool inside = true;
  double best = 1e30;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const V2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const V2 e = b - a;
    if (e.x() * (q - a).y() - e.y() * (q - a).x() < 0) inside = false;
    const double t = std::clamp((q - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + t * e - q).norm());
  }
  return inside ? 0.0 : best;
}

// The plane's view of a placement: unit normal, an in-plane basis, the footprint (the organ
// box's corners projected onto the plane, their hull).
struct PlaneView {
  V3 point, n, e1, e2;
  std::vector<V2> footprint;
  [[nodiscard]] double height(const V3& p) const { return (p - point).dot(n); }
  [[nodiscard]] V2 in_plane(const V3& p) const {
    return {(p - point).dot(e1), (p - point).dot(e2)};
  }
  [[nodiscard]] double footprint_distance(const V3& p) const {
    return polygon_distance(in_plane(p), footprint);
  }
};

PlaneView plane_view(const AbdomenPlacement& a) {
  PlaneView v;
  v.point = v3(a.point_m);
  v.n = v3(a.normal).normalized();
  v.e1 = v.n.unitOrthogonal();
  v.e2 = v.n.cross(v.e1);
  std::vector<V2> corners;
  const V3 lo = v3(a.organs_lo_m), hi = v3(a.organs_hi_m);
  for (int c = 0; c < 8; ++c)
    corners.push_back(v.in_plane(
        V3((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z())));
  v.footprint = hull(corners);
  return v;
}

double box_distance(const V3& p, const AbdomenPlacement& a) {
  const V3 lo = v3(a.organs_lo_m), hi = v3(a.organs_hi_m);
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

TEST(Scenery, MeshIsValidWithUnitNormalsAndEveryMaterial) {
  const AbdomenDimensions dims;
  for (const AbdomenPlacement& a : placements()) {
    const Scenery s = make_abdomen(a, dims);
    RenderFrame f;
    f.scenery = s;
    EXPECT_TRUE(validate(f).empty());
    ASSERT_EQ(s.nrm.size(), s.pos.size());
    ASSERT_EQ(s.material.size(), s.num_triangles());
    for (const std::uint32_t id : s.tri) ASSERT_LT(id, s.num_vertices());
    for (std::size_t i = 0; i < s.num_vertices(); ++i) {
      const V3 n(s.nrm[3 * i], s.nrm[3 * i + 1], s.nrm[3 * i + 2]);
      ASSERT_TRUE(vertex(s, i).allFinite() && n.allFinite()) << "vertex " << i;
      ASSERT_NEAR(n.norm(), 1.0, 1e-4) << "vertex " << i;
    }
    // The wall: (cells + 1)^2 vertices, 2 cells^2 triangles; bowel and fat besides.
    const auto cells = static_cast<std::size_t>(dims.wall_cells);
    ASSERT_GT(s.num_vertices(), (cells + 1) * (cells + 1));
    EXPECT_EQ(std::count(s.material.begin(), s.material.end(), SceneryMaterial::kPeritoneum),
              static_cast<std::ptrdiff_t>(2 * cells * cells));
    EXPECT_GT(std::count(s.material.begin(), s.material.end(), SceneryMaterial::kBowel), 5000);
    EXPECT_GT(std::count(s.material.begin(), s.material.end(), SceneryMaterial::kFat), 500);
    EXPECT_EQ(s.version, content_version(s));
    EXPECT_NE(s.version, 0u);
  }
  EXPECT_EQ(content_version(Scenery{}), 0u);
  // A bad id, a missing material and a NaN are each reported.
  RenderFrame f;
  f.scenery = make_abdomen(flat_placement());
  f.scenery.tri[5] = static_cast<std::uint32_t>(f.scenery.num_vertices());
  f.scenery.material.pop_back();
  f.scenery.pos[1] = std::nanf("");
  EXPECT_EQ(validate(f).size(), 3u);
}

// The organs lie on the plane: within their footprint plus 1 cm the wall only dips below it.
// Around them it undulates both ways, within its amplitude; its far rim rises (the flanks).
TEST(Scenery, NothingRisesAboveThePlaneUnderTheOrgans) {
  const AbdomenDimensions dims;
  for (const AbdomenPlacement& a : placements()) {
    const Scenery s = make_abdomen(a, dims);
    const PlaneView v = plane_view(a);
    std::size_t under = 0;
    double highest_under = -1.0, highest_near = -1.0, lowest_near = 1.0, highest_rim = -1.0;
    for (std::size_t i = 0; i < s.num_vertices(); ++i) {
      const V3 p = vertex(s, i);
      if (v.footprint_distance(p) <= dims.wall_clearance_m) {
        ++under;
        highest_under = std::max(highest_under, v.height(p));
      }
    }
    for (std::size_t t = 0; t < s.num_triangles(); ++t) {
      if (s.material[t] != SceneryMaterial::kPeritoneum) continue;
      const V3 p = vertex(s, s.tri[3 * t]);
      const double h = v.height(p);
      highest_rim = std::max(highest_rim, h);
      if (v.footprint_distance(p) > 0.15) continue;  // well within the flat part
      highest_near = std::max(highest_near, h);
      lowest_near = std::min(lowest_near, h);
    }
    EXPECT_GT(under, 500u);  // the grid is fine under the organs
    EXPECT_LE(highest_under, 1e-6);
    EXPECT_GT(highest_near, 0.5 * dims.wall_amplitude_m);  // it does undulate
    EXPECT_LE(highest_near, dims.wall_amplitude_m + 1e-6);
    EXPECT_GE(lowest_near, -2.0 * dims.wall_amplitude_m - 1e-6);
    EXPECT_GT(highest_rim, 0.04);
  }
}

// Bowel and fat keep 1.5 cm from the organs' footprint (so out of their box), lying on the plane:
// the tubes' lowest points on it, nothing higher than the thickest loop; the fat lobules sunk a
// little into the wall.
TEST(Scenery, BowelAndFatStayOutOfTheOrgansBox) {
  const AbdomenDimensions dims;
  for (const AbdomenPlacement& a : placements()) {
    const Scenery s = make_abdomen(a, dims);
    const PlaneView v = plane_view(a);
    std::vector<int> kind(s.num_vertices(), -1);  // the material of the triangles using it
    for (std::size_t t = 0; t < s.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) kind[s.tri[3 * t + k]] = static_cast<int>(s.material[t]);
    double nearest_footprint = 1.0, nearest_box = 1.0, highest = -1.0;
    std::array<double, 3> lowest{1.0, 1.0, 1.0};
    for (std::size_t i = 0; i < s.num_vertices(); ++i) {
      if (kind[i] <= static_cast<int>(SceneryMaterial::kPeritoneum)) continue;
      const V3 p = vertex(s, i);
      nearest_footprint = std::min(nearest_footprint, v.footprint_distance(p));
      nearest_box = std::min(nearest_box, box_distance(p, a));
      double& low = lowest[static_cast<std::size_t>(kind[i])];
      low = std::min(low, v.height(p));
      highest = std::max(highest, v.height(p));
    }
    EXPECT_GE(nearest_footprint, dims.bowel_clearance_m - 1e-4);
    EXPECT_GE(nearest_box, dims.bowel_clearance_m - 1e-4);
    EXPECT_NEAR(lowest[static_cast<std::size_t>(SceneryMaterial::kBowel)], 0.0, 1e-4);
    EXPECT_LT(lowest[static_cast<std::size_t>(SceneryMaterial::kFat)], 0.0);
    EXPECT_GT(lowest[static_cast<std::size_t>(SceneryMaterial::kFat)], -0.01);
    EXPECT_LE(highest, 2.0 * dims.bowel_radius_max_m + 1e-4);
  }
}

TEST(Scenery, IsDeterministic) {
  const Scenery a = make_abdomen(flat_placement());
  const Scenery b = make_abdomen(flat_placement());
  EXPECT_EQ(a.pos, b.pos);
  EXPECT_EQ(a.nrm, b.nrm);
  EXPECT_EQ(a.tri, b.tri);
  EXPECT_EQ(a.material, b.material);
  EXPECT_EQ(a.version, b.version);
  AbdomenPlacement moved = flat_placement();
  moved.point_m[2] = -0.005f;
  EXPECT_NE(make_abdomen(moved).version, a.version);
}

class SceneryPictures : public fixtures::PictureTest {};

// A 2 cm organ resting on the plane z = 0, an endoscope 11 cm above it looking down.
RenderFrame organ_from_above() {
  fixtures::Surface s = fixtures::icosphere(3, 0.02f);
  for (std::size_t i = 2; i < s.pos.size(); i += 3) s.pos[i] += 0.02f;
  RenderFrame f = fixtures::frame_of(s);
  f.group_names = {"", "appendix"};
  f.camera.eye = {0.0f, 0.0f, 0.15f};
  f.camera.target = {0.0f, 0.0f, 0.0f};
  f.camera.up = {0.0f, 1.0f, 0.0f};
  f.camera.fov_y_deg = 70.0f;
  return f;
}

// Without scenery two thirds and more of the picture is the background; with it no single colour
// takes a fifth, and the organ in the middle looks the same.
TEST_F(SceneryPictures, AbdomenFillsTheViewAroundTheOrgan) {
  RenderFrame f = organ_from_above();
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  o.lens = false;  // the optic's vignette would shade the background
  const Image bare = shoot(f, o, "scenery_none");
  f.scenery = make_abdomen(flat_placement());
  const Image abdomen = shoot(f, o, "scenery_abdomen");

  const DominantColor without = most_common_color(bare);
  const DominantColor with = most_common_color(abdomen);
  const auto bg = [&](std::size_t k) {
    return static_cast<std::uint8_t>(std::lround(o.background[k] * 255.0f));
  };
  EXPECT_EQ(without.rgb, (std::array<std::uint8_t, 3>{bg(0), bg(1), bg(2)}));
  EXPECT_GT(without.fraction, 0.5);
  EXPECT_LT(with.fraction, 0.2) << "most common colour " << int{with.rgb[0]} << ","
                                << int{with.rgb[1]} << "," << int{with.rgb[2]};
  EXPECT_GT(fixtures::coverage_fraction(abdomen), 0.99);  // no background left
  // The organ in the middle is drawn as before (its depth range differs, not its colours).
  const auto a = bare.at(160, 120), b = abdomen.at(160, 120);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], 2) << "channel " << k;
  // Pink bowel and yellow fat show somewhere around it.
  EXPECT_GT(fixtures::count_pixels(abdomen, [](int, int g, int bl) { return g > bl + 40; }), 100u)
      << "no fat-yellow pixels";
  std::printf("most common colour: without scenery %.3f, with %.3f\n", without.fraction,
              with.fraction);
}

// The mechanical and collision views leave the scenery out: the same pictures with and without.
TEST_F(SceneryPictures, OtherViewsLeaveItOut) {
  RenderFrame f = organ_from_above();
  SnapshotOptions o;
  o.width = 160;
  o.height = 120;
  for (const auto view : {SnapshotOptions::View::kCollision, SnapshotOptions::View::kMechanical}) {
    o.view = view;
    f.scenery = Scenery{};
    const Image bare = render_image(*ctx_, f, o);
    f.scenery = make_abdomen(flat_placement());
    const Image abdomen = render_image(*ctx_, f, o);
    EXPECT_EQ(bare.rgba, abdomen.rgba) << "view " << static_cast<int>(view);
  }
}

// One upload per scenery version, however many frames draw it; a new version uploads again.
TEST_F(SceneryPictures, RendererUploadsTheSceneryOncePerVersion) {
  RenderFrame f = organ_from_above();
  f.scenery = make_abdomen(flat_placement());
  SnapshotOptions o;
  o.width = 160;
  o.height = 120;
  ctx_->resize(o.width, o.height);
  FrameRenderer r;
  for (int i = 0; i < 3; ++i) {
    ctx_->bind_framebuffer();
    for (std::size_t k = 2; k < f.pos.size(); k += 3) f.pos[k] += 0.001f;  // organs move
    r.draw(f, o, o.width, o.height);
  }
  EXPECT_EQ(r.scenery_uploads(), 1u);
  EXPECT_GT(fixtures::coverage_fraction(ctx_->read_image()), 0.99);
  AbdomenPlacement lower = flat_placement();
  lower.point_m[2] = -0.01f;
  f.scenery = make_abdomen(lower);
  ctx_->bind_framebuffer();
  r.draw(f, o, o.width, o.height);
  EXPECT_EQ(r.scenery_uploads(), 2u);
  f.scenery = Scenery{};  // gone again: the void around the organ
  ctx_->bind_framebuffer();
  r.draw(f, o, o.width, o.height);
  EXPECT_EQ(r.scenery_uploads(), 3u);
  EXPECT_LT(fixtures::coverage_fraction(ctx_->read_image()), 0.5);
}

}  // namespace
}  // namespace serosa::render
