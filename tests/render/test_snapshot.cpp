// Headless pictures through EGL (Mesa llvmpipe in CI): the context, the visual view with Phong
// tessellation, group and wound materials, and the paper's three views. Images are compared by
// robust statistics (coverage, pixel classes, means), never pixel by pixel. Every test writes its
// PNGs under <build>/test-output/render/ for a person to look at.
//
// A machine without an offscreen OpenGL 4 context FAILS these tests rather than skipping them:
// CI installs Mesa (libegl1-mesa-dev, libgl1-mesa-dri), so a missing context is a real problem.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>

#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/picture_test.h"
#include "render/png_writer.h"
#include "render/render_fixtures.h"
#include "render/scaled_target.h"
#include "render/snapshot.h"

namespace serosa::render {
namespace {

using fixtures::coverage;
using fixtures::coverage_fraction;
using fixtures::mask_difference;
using fixtures::output_path;
using View = SnapshotOptions::View;

class Snapshot : public fixtures::PictureTest {};

TEST_F(Snapshot, ContextIsOpenGL4CoreAndClears) {
  EXPECT_FALSE(ctx_->gl_renderer().empty());
  ASSERT_GE(ctx_->gl_version().size(), 3u);
  const int major = ctx_->gl_version()[0] - '0';
  const int minor = ctx_->gl_version()[2] - '0';
  EXPECT_TRUE(major > 4 || (major == 4 && minor >= 1)) << ctx_->gl_version();
  RecordProperty("gl_version", ctx_->gl_version());
  RecordProperty("gl_renderer", ctx_->gl_renderer());
  RecordProperty("egl_platform", ctx_->egl_platform());

  // An empty frame: only the background, alpha 0 everywhere.
  SnapshotOptions o;
  o.width = 64;
  o.height = 48;
  const Image img = render_image(*ctx_, RenderFrame{}, o);
  ASSERT_EQ(img.width, 64);
  ASSERT_EQ(img.height, 48);
  EXPECT_EQ(coverage_fraction(img), 0.0);
  const auto px = img.at(10, 10);
  EXPECT_NEAR(px[0], std::lround(o.background[0] * 255.0f), 1);
  EXPECT_NEAR(px[1], std::lround(o.background[1] * 255.0f), 1);
}

TEST_F(Snapshot, SphereIsVisibleAndFramed) {
  auto f = fixtures::frame_of(fixtures::icosphere(2, 0.02f));  // a 2 cm radius organ
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  o.fit_camera = true;
  const Image img = shoot(f, o, "sphere_visual");
  const double cov = coverage_fraction(img);
  EXPECT_GT(cov, 0.10);
  EXPECT_LT(cov, 0.70);
  // Lit: the brightest covered pixels are much brighter than the background, and the wet
  // highlight reaches near white.
  const std::size_t bright = fixtures::count_pixels(
      img, [](int r, int g, int b) { return r > 230 && g > 200 && b > 200; });
  EXPECT_GT(bright, 10u);
  // Upside up: the image is not flipped (the camera looks from above, so the top half of the
  // picture shows the sphere's top; at least the picture is centred vertically within 20%).
  double cy = 0.0;
  std::size_t n = 0;
  const auto m = coverage(img);
  for (int y = 0; y < img.height; ++y) {
    for (int x = 0; x < img.width; ++x) {
      if (m[static_cast<std::size_t>(y * img.width + x)] != 0) {
        cy += y;
        ++n;
      }
    }
  }
  ASSERT_GT(n, 0u);
  EXPECT_NEAR(cy / static_cast<double>(n) / img.height, 0.5, 0.1);
}

// On a coarse icosahedron, level 3 bulges the flat faces out toward the sphere the normals
// describe: the silhouette changes, and gets closer to the true sphere's disc.
TEST_F(Snapshot, TessellationLevelChangesSilhouetteTowardTheSphere) {
  const float radius = 1.0f;
  const float distance = 4.0f;
  auto f = fixtures::frame_of(fixtures::icosahedron(radius), 1, distance);
  // Exact sphere normals at the vertices (radial).
  for (std::size_t i = 0; i < f.pos.size(); ++i) f.nrm[i] = f.pos[i] / radius;
  SnapshotOptions o;
  o.width = 256;
  o.height = 256;
  o.tessellation = 1;
  const Image flat = shoot(f, o, "icosahedron_level1");
  o.tessellation = 3;
  const Image level3 = shoot(f, o, "icosahedron_level3");
  o.tessellation = 8;
  const Image level8 = shoot(f, o, "icosahedron_level8");

  // The sphere's silhouette seen from distance d on the axis is a disc of angular radius
  // asin(r / d); in pixels (square pixels): (h / 2) tan(asin(r / d)) / tan(fov / 2).
  const double fov = static_cast<double>(f.camera.fov_y_deg) * std::numbers::pi / 180.0;
  const double disc_px = 0.5 * o.height *
                         std::tan(std::asin(static_cast<double>(radius / distance))) /
                         std::tan(0.5 * fov);
  std::vector<std::uint8_t> disc(static_cast<std::size_t>(o.width * o.height));
  for (int y = 0; y < o.height; ++y) {
    for (int x = 0; x < o.width; ++x) {
      const double dx = x + 0.5 - 0.5 * o.width;
      const double dy = y + 0.5 - 0.5 * o.height;
      disc[static_cast<std::size_t>(y * o.width + x)] = std::hypot(dx, dy) <= disc_px ? 1 : 0;
    }
  }
  const auto m1 = coverage(flat);
  const auto m3 = coverage(level3);
  const auto m8 = coverage(level8);
  const std::size_t changed = mask_difference(m1, m3);
  const std::size_t err1 = mask_difference(m1, disc);
  const std::size_t err3 = mask_difference(m3, disc);
  const std::size_t err8 = mask_difference(m8, disc);
  RecordProperty("silhouette_changed_px", static_cast<int>(changed));
  RecordProperty("disc_error_level1_px", static_cast<int>(err1));
  RecordProperty("disc_error_level3_px", static_cast<int>(err3));
  RecordProperty("disc_error_level8_px", static_cast<int>(err8));
  // 0.5% of the picture changes, and the error against the disc drops by at least a third.
  EXPECT_GT(changed, static_cast<std::size_t>(0.005 * o.width * o.height));
  EXPECT_LT(3 * err3, 2 * err1) << "level 1 error " << err1 << " px, level 3 " << err3 << " px";
  EXPECT_LT(err8, err1);
  // Shape factor 0 is flat whatever the level.
  o.shape_factor = 0.0f;
  const Image alpha0 = render_image(*ctx_, f, o);
  EXPECT_LT(mask_difference(coverage(alpha0), m1),
            static_cast<std::size_t>(0.001 * o.width * o.height));
}

// Two groups on one sphere (appendix above, mesoappendix below): both materials show.
TEST_F(Snapshot, TwoGroupsShowTheirMaterials) {
  auto f = fixtures::frame_of(fixtures::icosphere(2, 0.02f));
  f.group_names = {"", "appendix", "mesoappendix"};
  for (std::size_t t = 0; t < f.num_triangles(); ++t) {
    float cy = 0.0f;
    for (std::size_t k = 0; k < 3; ++k) cy += f.pos[3 * f.tri[3 * t + k] + 1];
    f.tri_group[t] = cy > 0.0f ? 1 : 2;
  }
  SnapshotOptions o;
  o.fit_camera = true;
  o.width = 320;
  o.height = 240;
  o.detail = false;  // the materials' own colours, without vessels and lobules over them
  const Image img = shoot(f, o, "two_groups_visual");
  // Pink: red clearly above green and green ~ blue; fat yellow: green close to red, blue low.
  const std::size_t pink = fixtures::count_pixels(
      img, [](int r, int g, int b) { return r > 60 && g * 10 < r * 8 && std::abs(g - b) < 20; });
  const std::size_t yellow = fixtures::count_pixels(
      img, [](int r, int g, int b) { return r > 60 && g * 10 > r * 8 && b * 10 < g * 8; });
  const std::size_t covered = static_cast<std::size_t>(coverage_fraction(img) * 320 * 240);
  RecordProperty("pink_px", static_cast<int>(pink));
  RecordProperty("yellow_px", static_cast<int>(yellow));
  EXPECT_GT(pink, covered / 5);
  EXPECT_GT(yellow, covered / 5);
  EXPECT_EQ(fixtures::count_pixels(img, fixtures::is_wound_red), 0u);
}

// Faces flagged as cut take the wound material whatever their group.
TEST_F(Snapshot, WoundFacesShowTheWoundColour) {
  auto f = fixtures::frame_of(fixtures::icosphere(2, 0.02f));
  f.group_names = {"", "appendix"};
  SnapshotOptions o;
  o.fit_camera = true;
  o.width = 320;
  o.height = 240;
  const Image intact = shoot(f, o, "wound_before");
  // Cut the cap facing the camera's side (+x +z).
  std::size_t cut = 0;
  for (std::size_t t = 0; t < f.num_triangles(); ++t) {
    float cx = 0.0f;
    float cz = 0.0f;
    for (std::size_t k = 0; k < 3; ++k) {
      cx += f.pos[3 * f.tri[3 * t + k]] / 3.0f;
      cz += f.pos[3 * f.tri[3 * t + k] + 2] / 3.0f;
    }
    if (cx + cz > 0.012f) {
      f.tri_cut[t] = 1;
      ++cut;
    }
  }
  ASSERT_GT(cut, 20u);
  f.topology_version = 1;
  const Image wounded = shoot(f, o, "wound_after");
  const std::size_t before = fixtures::count_pixels(intact, fixtures::is_wound_red);
  const std::size_t after = fixtures::count_pixels(wounded, fixtures::is_wound_red);
  const auto covered = static_cast<std::size_t>(coverage_fraction(wounded) * 320 * 240);
  RecordProperty("wound_px", static_cast<int>(after));
  EXPECT_EQ(before, 0u);
  EXPECT_GT(after, covered / 20) << "wound pixels " << after << " of " << covered;
}

// The paper's Figure 11 views of one mesh differ in coverage and colour.
TEST_F(Snapshot, ThreeViewsDiffer) {
  auto f = fixtures::frame_of(fixtures::icosphere(1, 0.02f));
  f.group_names = {"", "appendix"};
  fixtures::add_tet_fan_edges(f);
  SnapshotOptions o;
  o.fit_camera = true;
  o.width = 320;
  o.height = 240;
  o.lens = false;  // the optic's barrel distortion magnifies the centre of the visual view only
  o.view = View::kVisual;
  const Image visual = shoot(f, o, "views_visual");
  o.view = View::kCollision;
  const Image collision = shoot(f, o, "views_collision");
  o.view = View::kMechanical;
  const Image mechanical = shoot(f, o, "views_mechanical");

  const double cv = coverage_fraction(visual);
  const double cc = coverage_fraction(collision);
  const double cm = coverage_fraction(mechanical);
  RecordProperty("coverage_visual_permille", static_cast<int>(1000 * cv));
  RecordProperty("coverage_collision_permille", static_cast<int>(1000 * cc));
  RecordProperty("coverage_mechanical_permille", static_cast<int>(1000 * cm));
  // Visual and collision are both filled surfaces of about the same size (collision's is the
  // untessellated, slightly smaller polyhedron); the mechanical wireframe covers far less.
  EXPECT_GT(cv, 0.05);
  EXPECT_NEAR(cc / cv, 1.0, 0.1);
  EXPECT_GT(cm, 0.01);
  EXPECT_LT(cm, 0.8 * cc);
  // Colour: mean covered RGB differs between every pair by a clear margin.
  const auto mv = fixtures::mean_covered_rgb(visual);
  const auto mc = fixtures::mean_covered_rgb(collision);
  const auto mm = fixtures::mean_covered_rgb(mechanical);
  const auto dist = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                     (a[2] - b[2]) * (a[2] - b[2]));
  };
  EXPECT_GT(dist(mv, mc), 30.0);
  EXPECT_GT(dist(mv, mm), 30.0);
  EXPECT_GT(dist(mc, mm), 30.0);
  // Without tet edges the mechanical view falls back to the triangles' edges: still lines.
  f.edges.clear();
  const Image fallback = shoot(f, o, "views_mechanical_fallback");
  EXPECT_GT(coverage_fraction(fallback), 0.01);
  EXPECT_LT(coverage_fraction(fallback), cm);
}

// A renderer reused across frames: positions are re-read every draw (the sphere moves), indices
// follow the topology version.
TEST_F(Snapshot, RendererReuploadsPositionsEveryFrame) {
  auto f = fixtures::frame_of(fixtures::icosphere(2, 0.5f));
  SnapshotOptions o;
  o.width = 160;
  o.height = 120;
  ctx_->resize(o.width, o.height);
  ctx_->bind_framebuffer();
  FrameRenderer r;
  r.draw(f, o, o.width, o.height);
  const Image a = ctx_->read_image();
  for (std::size_t i = 0; i < f.pos.size(); i += 3) f.pos[i] += 0.8f;  // move right, same topology
  ctx_->bind_framebuffer();
  r.draw(f, o, o.width, o.height);
  const Image b = ctx_->read_image();
  EXPECT_GT(mask_difference(coverage(a), coverage(b)), 1000u);
  // Half the triangles under a new version: less coverage.
  f.tri.resize(f.tri.size() / 2);
  f.tri_group.resize(f.num_triangles());
  f.tri_cut.resize(f.num_triangles());
  f.topology_version = 7;
  ctx_->bind_framebuffer();
  r.draw(f, o, o.width, o.height);
  const Image c = ctx_->read_image();
  EXPECT_LT(coverage_fraction(c), coverage_fraction(b));
  // An invalid frame is refused before any GL call.
  f.tri.push_back(100000);
  f.tri.push_back(0);
  f.tri.push_back(1);
  EXPECT_THROW(r.draw(f, o, o.width, o.height), std::invalid_argument);
}

// The tessellated surface drawn in batches of patches (as on Mesa's software renderers) is the
// same picture, byte for byte, as drawn in one call, whatever the batch and however it divides
// the triangle count.
TEST_F(Snapshot, PatchesDrawnInBatchesGiveTheSamePicture) {
  auto f = fixtures::frame_of(fixtures::icosphere(2, 0.5f));  // 320 triangles
  SnapshotOptions o;
  o.width = 200;
  o.height = 160;
  o.tessellation = 3;
  ctx_->resize(o.width, o.height);
  FrameRenderer r;
  const auto picture = [&](std::size_t batch) {
    r.set_patches_per_draw(batch);
    ctx_->bind_framebuffer();
    r.draw(f, o, o.width, o.height);
    return ctx_->read_image();
  };
  const Image whole = picture(0);
  ASSERT_GT(coverage_fraction(whole), 0.05);
  for (const std::size_t batch :
       {std::size_t{1}, std::size_t{7}, FrameRenderer::kSoftwarePatchesPerDraw, std::size_t{1279},
        std::size_t{1280}, std::size_t{5000}})
    EXPECT_TRUE(picture(batch).rgba == whole.rgba) << batch << " patches a draw";
}

}  // namespace
}  // namespace serosa::render

namespace serosa::render {
namespace {

// Drawing at half the resolution and stretching it over the framebuffer (render/scaled_target.h)
// gives the same picture, a little softer: the same coverage, colours close to the full-size one.
TEST(ScaledTarget, HalfResolutionGivesTheSamePictureSofter) {
  std::unique_ptr<OffscreenContext> ctx;
  try {
    ctx = std::make_unique<OffscreenContext>(320, 240);
  } catch (const std::runtime_error& e) {
    GTEST_SKIP() << e.what();
  }
  FrameRenderer renderer;
  ScaledTarget target;
  const RenderFrame frame = fixtures::frame_of(fixtures::icosphere(3));
  SnapshotOptions options;
  auto draw = [&](float scale) {
    ctx->bind_framebuffer();
    int w = 0, h = 0;
    target.begin(320, 240, scale, w, h);
    renderer.draw(frame, options, w, h);
    target.present(320, 240);
    return std::make_pair(ctx->read_image(), std::make_pair(w, h));
  };
  const auto [full, full_size] = draw(1.0f);
  const auto [half, half_size] = draw(0.5f);
  EXPECT_EQ(full_size, std::make_pair(320, 240));
  EXPECT_EQ(half_size, std::make_pair(160, 120));
  std::int64_t covered_full = 0, covered_half = 0;
  double diff = 0.0;
  for (std::size_t p = 0; p + 3 < full.rgba.size(); p += 4) {
    covered_full += full.rgba[p + 3] > 128 ? 1 : 0;
    covered_half += half.rgba[p + 3] > 128 ? 1 : 0;
    for (std::size_t c = 0; c < 3; ++c)
      diff += std::abs(static_cast<int>(full.rgba[p + c]) - static_cast<int>(half.rgba[p + c]));
  }
  ASSERT_GT(covered_full, 5000);
  EXPECT_NEAR(static_cast<double>(covered_half), static_cast<double>(covered_full),
              0.05 * static_cast<double>(covered_full));
  EXPECT_LT(diff / (3.0 * 320 * 240), 12.0);  // mean absolute difference per channel, of 255
}

}  // namespace
}  // namespace serosa::render
