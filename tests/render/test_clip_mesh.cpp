// A placed clip's mesh (render/tool_mesh.h append_clip_mesh): two legs either side of its centre
// line, kClipGap apart, inside the clip's box, outward-facing, and a frame with a non-finite clip
// is refused.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>

#include "engine/clip.h"
#include "render/render_frame.h"
#include "render/tool_mesh.h"

namespace serosa::render {
namespace {

TEST(ClipMesh, TwoLegsAroundTheGapInsideTheClipsBox) {
  RenderClip c;
  c.start = {0.01f, 0.02f, 0.0f};
  c.end = {0.01f, 0.02f - static_cast<float>(kClipLength), 0.0f};
  c.across = {0.0f, 0.0f, 1.0f};
  ToolMesh m;
  append_clip_mesh(c, m);
  ASSERT_GT(m.num_triangles(), 12u);
  const float gap = static_cast<float>(kClipGap), hw = static_cast<float>(kClipHalfWidth);
  int near_side = 0, far_side = 0;
  for (std::size_t v = 0; v < m.num_vertices(); ++v) {
    const float x = m.pos[3 * v], y = m.pos[3 * v + 1], z = m.pos[3 * v + 2];
    EXPECT_LE(std::abs(x - 0.01f), hw + 1e-6f);
    EXPECT_LE(y, 0.02f + 1e-6f);
    EXPECT_GE(y, c.end[1] - kClipLegThickness - 1e-6f);
    EXPECT_LE(std::abs(z), 0.5f * gap + kClipLegThickness + 1e-6f);
    // Nothing of the legs inside the gap, short of the crown beyond the far end.
    if (y > c.end[1] + 1e-6f) {
      EXPECT_GE(std::abs(z), 0.5f * gap - 1e-6f);
    }
    (z > 0 ? near_side : far_side) += 1;
  }
  EXPECT_GT(near_side, 0);
  EXPECT_GT(far_side, 0);
  // Every triangle faces away from the leg it belongs to (normals agree with the winding).
  for (std::size_t t = 0; t < m.num_triangles(); ++t) {
    const auto p = [&](int k) {
      const std::uint32_t i = m.tri[3 * t + static_cast<std::size_t>(k)];
      return Eigen::Vector3f(m.pos[3 * i], m.pos[3 * i + 1], m.pos[3 * i + 2]);
    };
    const std::uint32_t i0 = m.tri[3 * t];
    const Eigen::Vector3f n(m.nrm[3 * i0], m.nrm[3 * i0 + 1], m.nrm[3 * i0 + 2]);
    EXPECT_GT((p(1) - p(0)).cross(p(2) - p(0)).dot(n), 0.0f) << "triangle " << t;
  }
}

TEST(ClipMesh, AFrameWithANonFiniteClipIsRefused) {
  RenderFrame f;
  f.clips.push_back(RenderClip{});
  EXPECT_TRUE(validate(f).empty());
  f.clips[0].end[1] = std::nanf("");
  const auto errors = validate(f);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("clips[0]"), std::string::npos);
}

}  // namespace
}  // namespace serosa::render
