// Instruments and the endoscope: tool meshes (geometry, no GL), the endoscope camera, and the
// pictures through EGL (tools visible, blades open and close, light falloff, angled scope).
// Pictures go to <build>/test-output/render/.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include "render/camera.h"
#include "render/gl_context.h"
#include "render/picture_test.h"
#include "render/png_writer.h"
#include "render/render_fixtures.h"
#include "render/snapshot.h"
#include "render/tool_mesh.h"

namespace serosa::render {
namespace {

using fixtures::coverage;
using fixtures::coverage_fraction;
using fixtures::mask_difference;

Eigen::Vector3f v3(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

std::array<float, 4> random_quat(std::mt19937& rng) {
  std::normal_distribution<float> n;
  Eigen::Quaternionf q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return {q.w(), q.x(), q.y(), q.z()};
}

// Largest distance of a steel (jaw) vertex from the tool's axis line through the hinge, m.
float jaw_spread(const ToolMesh& m, const ToolFrame& f) {
  const Eigen::Vector3f h = v3(f.hinge), a = v3(f.axis);
  float best = 0.0f;
  for (std::size_t i = 0; i < m.num_vertices(); ++i) {
    if (m.material[4 * i + 3] < 0.9f) continue;  // the shaft's coating, not steel
    const Eigen::Vector3f p(m.pos[3 * i], m.pos[3 * i + 1], m.pos[3 * i + 2]);
    const Eigen::Vector3f d = p - h;
    best = std::max(best, (d - d.dot(a) * a).norm());
  }
  return best;
}

TEST(ToolMesh, WellFormedFrameAndMeshForRandomPoses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.1f, 0.1f);
  std::uniform_real_distribution<float> jaw(0.0f, std::numbers::pi_v<float>);
  for (int i = 0; i < 200; ++i) {
    RenderTool t;
    t.kind = i % 2 == 0 ? RenderTool::Kind::kScissors : RenderTool::Kind::kGrasper;
    t.tip = {u(rng), u(rng), u(rng)};
    t.quat_wxyz = random_quat(rng);
    t.has_trocar = i % 3 != 0;
    t.trocar = {u(rng), u(rng), 0.15f + u(rng)};
    t.jaw_rad = jaw(rng);
    if (i == 0) t.quat_wxyz = {0.0f, 0.0f, 0.0f, 0.0f};  // degenerate: identity
    if (i == 1) t.trocar = t.tip;                        // degenerate: the pose's axis
    const ToolFrame f = tool_frame(t);
    const Eigen::Vector3f ax = v3(f.axis), up = v3(f.up), side = v3(f.side);
    EXPECT_NEAR(ax.norm(), 1.0f, 1e-5f);
    EXPECT_NEAR(up.norm(), 1.0f, 1e-5f);
    EXPECT_NEAR(ax.dot(up), 0.0f, 1e-5f);
    EXPECT_NEAR(side.dot(ax), 0.0f, 1e-5f);
    EXPECT_GT(side.dot(up.cross(ax)), 0.999f);  // right-handed: x = y cross z

    ToolMesh m;
    append_tool_mesh(t, m);
    ASSERT_EQ(m.pos.size(), m.nrm.size());
    ASSERT_EQ(m.material.size() / 4, m.num_vertices());
    ASSERT_GT(m.num_triangles(), 100u);
    for (const std::uint32_t id : m.tri) ASSERT_LT(id, m.num_vertices());
    for (std::size_t k = 0; k < m.num_vertices(); ++k) {
      const Eigen::Vector3f n(m.nrm[3 * k], m.nrm[3 * k + 1], m.nrm[3 * k + 2]);
      ASSERT_NEAR(n.norm(), 1.0f, 1e-4f);
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(m.pos[3 * k + c]));
    }
    // Closed jaws end at the tip: some jaw vertex lies within 2 mm of it (open: within the
    // jaw length of the hinge).
    if (t.jaw_rad < 1e-3f) {
      float near_tip = std::numeric_limits<float>::max();
      for (std::size_t k = 0; k < m.num_vertices(); ++k) {
        const Eigen::Vector3f p(m.pos[3 * k], m.pos[3 * k + 1], m.pos[3 * k + 2]);
        near_tip = std::min(near_tip, (p - v3(t.tip)).norm());
      }
      EXPECT_LT(near_tip, 2e-3f);
    }
  }
}

TEST(ToolMesh, ShaftRunsThroughTheTrocarToTheHinge) {
  RenderTool t;
  t.kind = RenderTool::Kind::kGrasper;
  t.tip = {0.03f, -0.02f, 0.06f};
  t.has_trocar = true;
  t.trocar = {-0.04f, -0.01f, 0.15f};
  // An orientation that disagrees with the trocar: the trocar wins for the axis.
  t.quat_wxyz = {1.0f, 0.0f, 0.0f, 0.0f};
  const ToolDimensions dims;
  const ToolFrame f = tool_frame(t, dims);
  const Eigen::Vector3f axis = (v3(t.tip) - v3(t.trocar)).normalized();
  EXPECT_GT(v3(f.axis).dot(axis), 0.9999f);
  // The trocar lies on the segment shaft_start -> hinge, strictly inside it.
  const Eigen::Vector3f s = v3(f.shaft_start), h = v3(f.hinge), c = v3(t.trocar);
  const float len = (h - s).norm();
  const float along = (c - s).dot((h - s) / len);
  EXPECT_GT(along, 0.05f);
  EXPECT_LT(along, len - 0.05f);
  EXPECT_LT(((c - s) - along * (h - s) / len).norm(), 1e-5f);
  // The shaft's surface vertices are all at the shaft radius from the axis (or on the caps).
  ToolMesh m;
  append_tool_mesh(t, m, dims);
  std::size_t on_radius = 0;
  for (std::size_t k = 0; k < m.num_vertices(); ++k) {
    if (m.material[4 * k + 3] > 0.9f) continue;  // jaws
    const Eigen::Vector3f p(m.pos[3 * k], m.pos[3 * k + 1], m.pos[3 * k + 2]);
    const Eigen::Vector3f d = p - s;
    const float r = (d - d.dot(axis) * axis).norm();
    EXPECT_LE(r, dims.shaft_radius * 1.001f);
    if (std::abs(r - dims.shaft_radius) < 1e-6f) ++on_radius;
  }
  EXPECT_GE(on_radius, 4u * static_cast<std::size_t>(dims.shaft_segments));
}

TEST(ToolMesh, JawsOpenWithTheJawAngle) {
  for (const auto kind : {RenderTool::Kind::kScissors, RenderTool::Kind::kGrasper}) {
    RenderTool t;
    t.kind = kind;
    t.tip = {0.0f, 0.0f, 0.0f};
    float previous = 0.0f;
    for (const float jaw : {0.0f, 0.2f, 0.5f, 0.9f, 1.4f}) {
      t.jaw_rad = jaw;
      ToolMesh m;
      append_tool_mesh(t, m);
      const float spread = jaw_spread(m, tool_frame(t));
      if (jaw == 0.0f) {
        EXPECT_LT(spread, 2.6e-3f);  // closed: within the 5 mm shaft's outline
      } else {
        EXPECT_GT(spread, previous + 0.5e-3f) << "jaw " << jaw;
      }
      // At least the blade's or jaw's length times sin(jaw / 2), at most that plus its width.
      const float len = kind == RenderTool::Kind::kScissors ? ToolDimensions{}.scissors_blade
                                                            : ToolDimensions{}.grasper_jaw;
      EXPECT_GE(spread, 0.95f * len * std::sin(0.5f * jaw));
      EXPECT_LE(spread, len * std::sin(0.5f * jaw) + 3e-3f);
      previous = spread;
    }
  }
}

TEST(EndoscopeCamera, ZeroAndAngledScopes) {
  std::mt19937 rng(3);
  for (int i = 0; i < 50; ++i) {
    const auto q = random_quat(rng);
    const Eigen::Quaternionf qq(q[0], q[1], q[2], q[3]);
    const Eigen::Matrix3f r = qq.toRotationMatrix();
    const std::array<float, 3> tip{0.01f, 0.02f, 0.1f};
    const Camera c0 = endoscope_camera(tip, q, 0.0f, 70.0f, 0.08f);
    const Eigen::Vector3f d0 = v3(c0.target) - v3(c0.eye);
    EXPECT_NEAR(d0.norm(), 0.08f, 1e-5f);
    EXPECT_GT(d0.normalized().dot(r.col(2)), 0.9999f);
    EXPECT_GT(v3(c0.up).normalized().dot(r.col(1)), 0.9999f);
    EXPECT_EQ(c0.fov_y_deg, 70.0f);
    EXPECT_EQ(c0.eye, tip);
    const Camera c30 = endoscope_camera(tip, q, 30.0f);
    const Eigen::Vector3f d30 = (v3(c30.target) - v3(c30.eye)).normalized();
    EXPECT_NEAR(
        std::acos(std::clamp(d30.dot(r.col(2)), -1.0f, 1.0f)) * 180.0f / std::numbers::pi_v<float>,
        30.0f, 0.05f);
    EXPECT_LT(d30.dot(r.col(1)), -0.49f);  // towards the image's down side
    EXPECT_NEAR(v3(c30.up).dot(d30), 0.0f, 1e-5f);
  }
}

TEST(RenderFrame, ValidateChecksTools) {
  RenderFrame f;
  f.tools.resize(3);
  f.tools[1].jaw_rad = 4.0f;
  f.tools[2].tip[1] = std::numeric_limits<float>::quiet_NaN();
  const auto errors = validate(f);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("tools[1]"), std::string::npos);
  EXPECT_NE(errors[1].find("tools[2]"), std::string::npos);
}

class ToolPictures : public fixtures::PictureTest {};

// A 2 cm organ at the origin, seen by an endoscope 8 cm away on +z, a grasper and scissors in
// front of it through trocars on the abdominal wall.
RenderFrame organ_with_tools(float scissors_jaw) {
  RenderFrame f = fixtures::frame_of(fixtures::icosphere(2, 0.02f));
  f.group_names = {"", "appendix"};
  // Looking along -z: the identity scope looks along +z, so turn it half around y.
  const std::array<float, 4> back{0.0f, 0.0f, 1.0f, 0.0f};
  f.camera = endoscope_camera({0.0f, 0.0f, 0.08f}, back, 0.0f, 70.0f, 0.08f);
  RenderTool g;
  g.kind = RenderTool::Kind::kGrasper;
  g.tip = {-0.012f, 0.006f, 0.03f};
  g.has_trocar = true;
  g.trocar = {-0.06f, 0.02f, 0.15f};
  g.jaw_rad = 0.5f;
  // Local +y (the jaws' hinge axis) towards the camera, so that the jaws open in the picture.
  g.quat_wxyz = {std::sqrt(0.5f), std::sqrt(0.5f), 0.0f, 0.0f};
  RenderTool s;
  s.kind = RenderTool::Kind::kScissors;
  s.tip = {0.012f, -0.004f, 0.03f};
  s.has_trocar = true;
  s.trocar = {0.07f, 0.0f, 0.15f};
  s.jaw_rad = scissors_jaw;
  s.quat_wxyz = g.quat_wxyz;
  f.tools = {g, s};
  return f;
}

// Grey, unsaturated pixels: steel and the black shafts (tissue is pink).
bool is_instrument(int r, int g, int b) { return std::max({r, g, b}) - std::min({r, g, b}) < 25; }

TEST_F(ToolPictures, ToolsAreVisibleInEveryView) {
  RenderFrame with = organ_with_tools(0.6f);
  RenderFrame without = with;
  without.tools.clear();
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  const Image a = shoot(without, o, "tools_none");
  const Image b = shoot(with, o, "tools_visual");
  const std::size_t grey_a = fixtures::count_pixels(a, is_instrument);
  const std::size_t grey_b = fixtures::count_pixels(b, is_instrument);
  RecordProperty("instrument_px", static_cast<int>(grey_b));
  // (The organ's wet highlight is white too: count what the tools add.)
  EXPECT_GT(grey_b, grey_a + 2000u);
  EXPECT_GT(coverage_fraction(b), coverage_fraction(a) + 0.03);
  // Both shafts run in from the picture's sides: covered pixels at the left and right edges.
  const auto m = coverage(b);
  std::size_t left = 0, right = 0;
  for (int y = 0; y < o.height; ++y) {
    left += m[static_cast<std::size_t>(y * o.width)];
    right += m[static_cast<std::size_t>(y * o.width + o.width - 1)];
  }
  EXPECT_GT(left, 3u);
  EXPECT_GT(right, 3u);
  for (const auto view : {SnapshotOptions::View::kCollision, SnapshotOptions::View::kMechanical}) {
    o.view = view;
    const Image c =
        shoot(with, o,
              view == SnapshotOptions::View::kCollision ? "tools_collision" : "tools_mechanical");
    EXPECT_GT(fixtures::count_pixels(c, is_instrument), 1000u);
  }
}

TEST_F(ToolPictures, ScissorsOpenAndClose) {
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  const Image closed = shoot(organ_with_tools(0.0f), o, "scissors_closed");
  const Image open = shoot(organ_with_tools(1.0f), o, "scissors_open");
  const std::size_t diff = mask_difference(coverage(closed), coverage(open));
  // Nothing but the blades differs; the open blades cover more.
  EXPECT_GT(diff, 150u);
  EXPECT_GT(fixtures::count_pixels(open, is_instrument),
            fixtures::count_pixels(closed, is_instrument));
}

// The guide (the planned cut) is a violet marker across the organ: where it runs outside the
// tissue it shows, blue above red; inside it is hidden; without a guide there is no violet.
TEST_F(ToolPictures, TheGuideMarksThePlannedCutWhereItLeavesTheTissue) {
  RenderFrame f = organ_with_tools(0.6f);
  f.tools.clear();
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  const auto violet = [](int r, int g, int b) { return b > r + 10 && b > g + 40; };
  EXPECT_EQ(fixtures::count_pixels(shoot(f, o, "guide_none"), violet), 0u);
  f.guide = {{-0.035f, 0.0f, 0.0f}, {0.035f, 0.0f, 0.0f}};  // through the 2 cm organ, along x
  const Image across = shoot(f, o, "guide_across");
  const std::size_t seen = fixtures::count_pixels(across, violet);
  EXPECT_GT(seen, 20u);
  f.guide = {{-0.005f, 0.0f, 0.0f}, {0.005f, 0.0f, 0.0f}};  // all inside the organ
  EXPECT_EQ(fixtures::count_pixels(shoot(f, o, "guide_inside"), violet), 0u);
}

// The light sits at the scope's tip: the same organ seen from twice as far (with the field of
// view narrowed to keep its size) is darker; an angled scope sees it elsewhere in the picture.
TEST_F(ToolPictures, EndoscopeLightFallsOffAndAngledScopeShiftsTheView) {
  RenderFrame f = fixtures::frame_of(fixtures::icosphere(2, 0.02f));
  f.group_names = {"", "appendix"};
  const std::array<float, 4> back{0.0f, 0.0f, 1.0f, 0.0f};
  SnapshotOptions o;
  o.width = 240;
  o.height = 240;
  f.camera = endoscope_camera({0.0f, 0.0f, 0.08f}, back, 0.0f, 70.0f, 0.08f);
  const Image near_img = shoot(f, o, "endoscope_near");
  const float fov_far = 2.0f *
                        std::atan(0.5f * std::tan(35.0f * std::numbers::pi_v<float> / 180.0f)) *
                        180.0f / std::numbers::pi_v<float>;
  f.camera = endoscope_camera({0.0f, 0.0f, 0.16f}, back, 0.0f, fov_far, 0.08f);
  const Image far_img = shoot(f, o, "endoscope_far");
  EXPECT_NEAR(coverage_fraction(far_img) / coverage_fraction(near_img), 1.0, 0.1);
  const auto lum = [](const Image& im) {
    const auto m = fixtures::mean_covered_rgb(im);
    return m[0] + m[1] + m[2];
  };
  RecordProperty("mean_rgb_sum_near", static_cast<int>(lum(near_img)));
  RecordProperty("mean_rgb_sum_far", static_cast<int>(lum(far_img)));
  EXPECT_LT(lum(far_img), 0.8 * lum(near_img));

  // 30 degree scope, same pose: it looks down, so the organ moves up in the picture.
  f.camera = endoscope_camera({0.0f, 0.0f, 0.08f}, back, 30.0f, 70.0f, 0.08f);
  const Image angled = shoot(f, o, "endoscope_30deg");
  const auto centroid_y = [](const Image& im) {
    const auto m = coverage(im);
    double sy = 0.0, n = 0.0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x)
        if (m[static_cast<std::size_t>(y * im.width + x)] != 0) {
          sy += y;
          n += 1.0;
        }
    return n > 0.0 ? sy / n / im.height : -1.0;
  };
  EXPECT_NEAR(centroid_y(near_img), 0.5, 0.05);
  EXPECT_LT(centroid_y(angled), 0.3);
  EXPECT_GT(centroid_y(angled), 0.0);
}

}  // namespace
}  // namespace serosa::render
