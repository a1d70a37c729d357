// Area-weighted vertex normals, frame validation, materials and camera fitting: the GL-free half
// of render/.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "render/camera.h"
#include "render/materials.h"
#include "render/render_fixtures.h"
#include "render/render_frame.h"
#include "render/vertex_normals.h"

namespace serosa::render {
namespace {

TEST(VertexNormals, IcosphereNormalsAreRadialAndUnit) {
  for (int levels : {0, 2}) {
    const auto s = fixtures::icosphere(levels, 0.03f);
    const auto n = compute_vertex_normals(s.pos, s.tri);
    ASSERT_EQ(n.size(), s.pos.size());
    for (std::size_t i = 0; i < n.size(); i += 3) {
      const float len = std::sqrt(n[i] * n[i] + n[i + 1] * n[i + 1] + n[i + 2] * n[i + 2]);
      EXPECT_NEAR(len, 1.0f, 1e-5f);
      // On a sphere the normal is the radial direction (up to the mesh's discretisation).
      const float dot =
          (n[i] * s.pos[i] + n[i + 1] * s.pos[i + 1] + n[i + 2] * s.pos[i + 2]) / 0.03f;
      EXPECT_GT(dot, 0.99f) << "vertex " << i / 3;
    }
  }
}

TEST(VertexNormals, AreaWeighting) {
  // Two triangles sharing vertex 0: a big one in the z = 0 plane and a small one in x = 0.
  const std::vector<float> pos{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0.1f, 0, -0.1f, 0};
  const std::vector<std::uint32_t> tri{0, 1, 2, 0, 3, 4};
  const auto n = compute_vertex_normals(pos, tri);
  // Big: +z with area 0.5; small: (0,0,.1)x(0,-.1,0) = (+0.01,0,0), area 0.005.
  EXPECT_NEAR(n[0], 0.01f / std::sqrt(1.0f + 0.0001f), 1e-4f);
  EXPECT_NEAR(n[2], 1.0f, 1e-4f);
  EXPECT_FLOAT_EQ(n[5], 1.0f);  // vertex 1 only touches the big one
}

TEST(VertexNormals, UnusedVertexIsZeroAndBadIdThrows) {
  const std::vector<float> pos{0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 5};
  const auto n = compute_vertex_normals(pos, std::vector<std::uint32_t>{0, 1, 2});
  EXPECT_EQ(n[9], 0.0f);
  EXPECT_EQ(n[10], 0.0f);
  EXPECT_EQ(n[11], 0.0f);
  EXPECT_THROW((void)compute_vertex_normals(pos, std::vector<std::uint32_t>{0, 1, 4}),
               std::invalid_argument);
}

TEST(RenderFrame, ValidateReportsEachProblem) {
  auto f = fixtures::frame_of(fixtures::icosahedron());
  EXPECT_TRUE(validate(f).empty());
  f.tri.push_back(99);
  f.tri.push_back(0);
  f.tri.push_back(1);
  f.edges = {0};
  const auto errors = validate(f);
  // tri uses vertex 99, tri_group and tri_cut no longer one per triangle, edges odd.
  EXPECT_EQ(errors.size(), 4u);
}

TEST(Materials, NamedGroupsAndDistinctWound) {
  RenderFrame f;
  f.group_names = {"", "appendix", "mesoappendix", "cecum", "unknown"};
  const Material app = group_material(f, 1);
  const Material meso = group_material(f, 2);
  const Material cec = group_material(f, 3);
  // Appendix pinkish (red > green ~ blue), mesoappendix yellowish (red ~ green > blue), cecum
  // darker than the appendix.
  EXPECT_GT(app.color[0], app.color[1] + 0.2f);
  EXPECT_GT(meso.color[1], meso.color[2] + 0.2f);
  EXPECT_LT(cec.color[0] + cec.color[1] + cec.color[2], app.color[0] + app.color[1] + app.color[2]);
  // The wound is far from every tissue colour, named or from the palette.
  const Material w = wound_material();
  for (std::uint16_t g = 0; g < 40; ++g) {
    const Material m = group_material(f, g);
    float d2 = 0.0f;
    for (int k = 0; k < 3; ++k) d2 += (m.color[k] - w.color[k]) * (m.color[k] - w.color[k]);
    EXPECT_GT(std::sqrt(d2), 0.3f) << "group " << g;
  }
}

TEST(Camera, AutoCameraFitsTheBoundsInView) {
  // A long box-like cloud off the origin, in mm-sized units: every vertex must project inside.
  auto s = fixtures::icosphere(1, 0.02f);
  for (std::size_t i = 0; i < s.pos.size(); i += 3) {
    s.pos[i] = 3.0f * s.pos[i] + 0.1f;
    s.pos[i + 1] -= 0.05f;
  }
  auto f = fixtures::frame_of(s);
  for (const float aspect : {0.5f, 4.0f / 3.0f, 2.5f}) {
    f.camera = auto_camera(f, aspect);
    const CameraMatrices m = camera_matrices(f.camera, aspect, drawn_bounds(f));
    for (std::size_t i = 0; i < s.pos.size(); i += 3) {
      const Eigen::Vector4f clip =
          m.projection * m.view * Eigen::Vector4f(s.pos[i], s.pos[i + 1], s.pos[i + 2], 1.0f);
      ASSERT_GT(clip.w(), 0.0f);
      const Eigen::Vector3f ndc = clip.head<3>() / clip.w();
      EXPECT_LT(ndc.cwiseAbs().maxCoeff(), 1.0f) << "aspect " << aspect << " vertex " << i / 3;
    }
    // The target projects to the centre of the picture.
    const Eigen::Vector4f c =
        m.projection * m.view *
        Eigen::Vector4f(f.camera.target[0], f.camera.target[1], f.camera.target[2], 1.0f);
    EXPECT_NEAR(c.x() / c.w(), 0.0f, 1e-5f);
    EXPECT_NEAR(c.y() / c.w(), 0.0f, 1e-5f);
  }
}

}  // namespace
}  // namespace serosa::render
