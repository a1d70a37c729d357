// The tissue's look: the pattern volume tiles without seams and has its features; the flatness
// statistic; pictures of tissue carry detail, the pattern stays on the tissue (rest positions)
// when it moves; the endoscope's optic darkens the corners and is the identity when switched off.
#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>

#include "engine/scene/scene.h"
#include "render/image_stats.h"
#include "render/lens_pass.h"
#include "render/materials.h"
#include "render/picture_test.h"
#include "render/tissue_pattern.h"

namespace serosa::render {
namespace {

using fixtures::PictureTest;

// Mean absolute difference of channel c between voxels one step apart along `axis`, across the
// volume's seam (last voxel to first) and inside it.
struct SeamStep {
  double seam = 0.0;
  double inside = 0.0;  // the largest over the interior slices
};
SeamStep seam_step(const TissuePattern& p, int axis, int c) {
  const int n = p.size;
  const auto at = [&](int x, int y, int z) {
    const std::size_t i = (static_cast<std::size_t>(z) * n + y) * n + x;
    return static_cast<double>(p.rgba[4 * i + static_cast<std::size_t>(c)]);
  };
  const auto step = [&](int a, int u, int v, int b) {
    std::array<int, 3> i{0, 0, 0}, j{0, 0, 0};
    i[axis] = a;
    j[axis] = b;
    i[(axis + 1) % 3] = j[(axis + 1) % 3] = u;
    i[(axis + 2) % 3] = j[(axis + 2) % 3] = v;
    return std::abs(at(i[0], i[1], i[2]) - at(j[0], j[1], j[2]));
  };
  SeamStep s;
  for (int a = 0; a < n; ++a) {
    double mean = 0.0;
    for (int u = 0; u < n; ++u)
      for (int v = 0; v < n; ++v) mean += step(a, u, v, (a + 1) % n);
    mean /= n * n;
    if (a == n - 1)
      s.seam = mean;
    else
      s.inside = std::max(s.inside, mean);
  }
  return s;
}

// Every tissue a scene's [render] looks may name is one the renderer draws.
TEST(TissueLooks, EveryLookTheSceneMayNameHasAMaterial) {
  for (const std::string_view look : kTissueLooks) {
    Material m;
    EXPECT_TRUE(named_material(look, m)) << look;
  }
}

TEST(TissuePattern, TilesWithoutSeamsOnEveryAxisAndChannel) {
  const TissuePattern& p = tissue_pattern();
  ASSERT_EQ(p.size, kTissuePatternSize);
  for (int axis = 0; axis < 3; ++axis)
    for (int c = 0; c < 4; ++c) {
      const SeamStep s = seam_step(p, axis, c);
      EXPECT_LE(s.seam, s.inside * 1.05) << "axis " << axis << " channel " << c;
    }
}

TEST(TissuePattern, DeterministicWithVesselsLobulesAndNoise) {
  const TissuePattern a = make_tissue_pattern(24);
  const TissuePattern b = make_tissue_pattern(24);
  EXPECT_EQ(a.rgba, b.rgba);
  const TissuePattern& p = tissue_pattern();
  const std::size_t voxels = p.rgba.size() / 4;
  std::array<double, 4> mean{}, high{};
  for (std::size_t i = 0; i < voxels; ++i)
    for (std::size_t c = 0; c < 4; ++c) {
      mean[c] += p.rgba[4 * i + c];
      high[c] += p.rgba[4 * i + c] > 128 ? 1.0 : 0.0;
    }
  for (std::size_t c = 0; c < 4; ++c) {
    mean[c] /= static_cast<double>(voxels);
    high[c] /= static_cast<double>(voxels);
  }
  // Vessels and lobule borders are thin lines: a minority of the volume, but present.
  EXPECT_GT(high[kVessels], 0.04);
  EXPECT_LT(high[kVessels], 0.35);
  EXPECT_GT(high[kLobules], 0.04);
  EXPECT_LT(high[kLobules], 0.40);
  // Mottle and relief vary about mid-grey.
  EXPECT_NEAR(mean[kMottle], 128.0, 25.0);
  EXPECT_NEAR(mean[kRelief], 128.0, 25.0);
  EXPECT_THROW((void)make_tissue_pattern(3), std::invalid_argument);
}

Image solid(int w, int h, std::uint8_t v) {
  Image img{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(4 * w * h), v)};
  return img;
}

TEST(FlatBlocks, UniformAndSmoothPicturesAreFlatNoiseIsNot) {
  EXPECT_DOUBLE_EQ(flat_block_fraction(solid(64, 48, 90)), 1.0);
  Image ramp = solid(64, 48, 0);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x)
      for (int c = 0; c < 3; ++c)
        ramp.rgba[static_cast<std::size_t>(4 * (y * 64 + x) + c)] =
            static_cast<std::uint8_t>(2 * x + y);
  EXPECT_DOUBLE_EQ(flat_block_fraction(ramp), 1.0);  // smooth shading is no detail
  Image noisy = solid(64, 48, 0);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> u(60, 200);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 30; ++x)  // the left two tiles (the third's 5 x 5 mean stays clear of it)
      for (int c = 0; c < 3; ++c)
        noisy.rgba[static_cast<std::size_t>(4 * (y * 64 + x) + c)] =
            static_cast<std::uint8_t>(u(rng));
  EXPECT_NEAR(flat_block_fraction(noisy), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(flat_block_fraction(solid(8, 8, 0)), 0.0);  // smaller than one tile
}

// An icosphere of 5 cm radius seen from 4 cm above its surface, as the endoscope sees the organs:
// it fills the picture.
RenderFrame tissue_in_view(std::uint16_t group) {
  const fixtures::Surface s = fixtures::icosphere(4, 0.05f);
  RenderFrame f = fixtures::frame_of(s, group, 0.09f);
  f.camera.target = {0.0f, 0.0f, 0.05f};  // the surface point in front: the light's reference
  f.camera.fov_y_deg = 50.0f;
  f.group_names = {"", "appendix", "mesoappendix"};
  return f;
}

TEST_F(PictureTest, TissueCarriesDetailWhereShadingAloneWouldBeFlat) {
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  for (std::uint16_t g : {1, 2}) {
    const RenderFrame f = tissue_in_view(g);
    const Image img = shoot(f, o, g == 1 ? "tissue_appendix" : "tissue_fat");
    EXPECT_LT(flat_block_fraction(img), 0.35) << "group " << g;
    SnapshotOptions plain = o;
    plain.detail = false;
    EXPECT_GT(flat_block_fraction(render_image(*ctx_, f, plain)), 0.6) << "group " << g;
  }
}

double mean_abs_difference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    sum += std::abs(static_cast<int>(a.rgba[i]) - static_cast<int>(b.rgba[i]));
  return sum / static_cast<double>(a.rgba.size());
}

TEST_F(PictureTest, ThePatternMovesWithTheTissueNotWithTheWorld) {
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  RenderFrame still = tissue_in_view(1);
  still.rest = still.pos;
  const Image base = render_image(*ctx_, still, o);
  // Tissue and endoscope moved together by 7 mm: the same picture, since the pattern is laid out
  // in the rest positions.
  RenderFrame moved = still;
  const std::array<float, 3> d{0.007f, -0.004f, 0.003f};
  for (std::size_t i = 0; i < moved.pos.size(); ++i) moved.pos[i] += d[i % 3];
  for (int k = 0; k < 3; ++k) {
    moved.camera.eye[static_cast<std::size_t>(k)] += d[static_cast<std::size_t>(k)];
    moved.camera.target[static_cast<std::size_t>(k)] += d[static_cast<std::size_t>(k)];
  }
  EXPECT_LT(mean_abs_difference(base, render_image(*ctx_, moved, o)), 0.5);
  // Laid out in the moved positions instead, the pattern slides over the tissue.
  RenderFrame slid = moved;
  slid.rest = slid.pos;
  EXPECT_GT(mean_abs_difference(base, render_image(*ctx_, slid, o)), 3.0);
}

// The cecum's taeniae show as pale bands where the frame says they run; other tissue ignores
// them.
TEST_F(PictureTest, TheCecumsTaeniaeRunWhereTheFrameSays) {
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  RenderFrame f = tissue_in_view(1);
  f.group_names = {"", "cecum"};
  f.rest = f.pos;
  const Image plain = render_image(*ctx_, f, o);
  f.taenia_centre = {0.0f, 0.0f, 0.0f};
  f.taenia_axis = {0.0f, 0.0f, 1.0f};  // converging on the point facing the scope
  const Image banded = shoot(f, o, "tissue_cecum_taeniae");
  EXPECT_GT(mean_abs_difference(plain, banded), 1.0);
  f.group_names = {"", "appendix"};
  RenderFrame without = f;
  without.taenia_axis = {0.0f, 0.0f, 0.0f};
  const Image appendix = render_image(*ctx_, f, o);
  EXPECT_EQ(appendix.rgba, render_image(*ctx_, without, o).rgba);
}

// A puff of smoke between the scope and the tissue greys the picture where it lies, and only
// there; the coverage (alpha) stays the tissue's. Behind the tissue it is hidden.
TEST_F(PictureTest, SmokeVeilsTheTissueInFrontOfItOnly) {
  SnapshotOptions o;
  o.width = 320;
  o.height = 240;
  o.lens = false;
  RenderFrame f = tissue_in_view(1);
  const Image clear = render_image(*ctx_, f, o);
  f.smoke.push_back({{0.0f, 0.0f, 0.06f}, 0.008f, 0.9f});  // 1 cm in front of the surface
  const Image smoky = render_image(*ctx_, f, o);
  const auto saturation = [](const Image& img, int x, int y) {
    const auto p = img.at(x, y);
    return static_cast<double>(std::max({p[0], p[1], p[2]}) - std::min({p[0], p[1], p[2]}));
  };
  // Its centre: greyer, nearer the smoke's colour than the tissue; the corners untouched.
  EXPECT_LT(saturation(smoky, 160, 120), 0.6 * saturation(clear, 160, 120));
  const auto to_smoke = [](const Image& img, int x, int y) {
    const auto p = img.at(x, y);
    return std::abs(p[0] - 219) + std::abs(p[1] - 214) + std::abs(p[2] - 204);
  };
  EXPECT_LT(to_smoke(smoky, 160, 120), to_smoke(clear, 160, 120));
  EXPECT_EQ(smoky.at(5, 5), clear.at(5, 5));
  for (std::size_t i = 3; i < clear.rgba.size(); i += 4) ASSERT_EQ(smoky.rgba[i], clear.rgba[i]);
  // Behind the sphere's front (inside it): hidden.
  f.smoke.back().at = {0.0f, 0.0f, 0.0f};
  EXPECT_LT(mean_abs_difference(render_image(*ctx_, f, o), clear), 0.01);
}

TEST_F(PictureTest, EndoscopeOpticDarkensTheCornersAndIsTheIdentityWhenOff) {
  constexpr int kW = 160, kH = 120;
  ctx_->resize(kW, kH);
  LensPass lens;
  const auto draw = [&](const LensSettings& s) {
    ctx_->bind_framebuffer();  // read_image leaves none bound
    lens.begin(kW, kH);
    // A checkerboard of 8-pixel squares.
    glEnable(GL_SCISSOR_TEST);
    for (int y = 0; y < kH; y += 8)
      for (int x = 0; x < kW; x += 8) {
        glScissor(x, y, 8, 8);
        const float v = ((x / 8 + y / 8) % 2 == 0) ? 0.8f : 0.4f;
        glClearColor(v, v, v, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
      }
    glDisable(GL_SCISSOR_TEST);
    lens.end(s);
    return ctx_->read_image();
  };
  const Image plain = draw(LensSettings{0.0f, 0.0f, false});
  for (int y = 0; y < kH; y += 7)
    for (int x = 0; x < kW; x += 5) {
      const int expect = ((x / 8 + (kH - 1 - y) / 8) % 2 == 0) ? 204 : 102;
      ASSERT_NEAR(plain.at(x, y)[0], expect, 1) << x << "," << y;
    }
  const Image optic = draw(LensSettings{0.06f, 0.35f, false});
  // The corner keeps 65 % of its light; the centre all of it (a pixel inside the square at the
  // centre, which the distortion moves by less than a pixel).
  EXPECT_EQ(optic.at(kW / 2 + 3, kH / 2 - 3)[0], plain.at(kW / 2 + 3, kH / 2 - 3)[0]);
  const double corner = optic.at(0, 0)[0];
  EXPECT_TRUE(std::abs(corner - 0.65 * 204) < 3 || std::abs(corner - 0.65 * 102) < 3) << corner;
  // The barrel distortion magnifies the centre by 1 + k: a square edge 16 px from the centre
  // moves about a pixel outwards, so the two pictures differ near it but not at the centre.
  EXPECT_GT(mean_abs_difference(plain, optic), 1.0);
}

}  // namespace
}  // namespace serosa::render
