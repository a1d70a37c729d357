// What a person sees in the pictures of a simulated cut, drawn by the headless picture path
// (app/frame_pictures.h, used by `serosa headless --frames` and `serosa replay --frames`): the
// organs, the instruments at their poses, the wound after a cut (wound-material pixels, a dark
// saturated red no tissue material has: none before the cut, a patch after) and the paper's three
// views, which differ. Images are compared by robust statistics, never pixel by pixel. PNGs go to
// <build>/test-output/render/ for a person to look at.
//
// OpenGL comes from EGL (Mesa llvmpipe in CI): no display needed. A machine without an offscreen
// OpenGL 4 context FAILS these tests (CI installs Mesa), as the render tests do.
#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app/frame_pictures.h"
#include "app/headless.h"
#include "cutting/cut_mesh.h"
#include "cutting/cutting_stage.h"
#include "cutting/validate.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/topology_delta.h"
#include "render/image.h"
#include "render/png_writer.h"
#include "support/test_paths.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;
using View = FramePictures::View;

fs::path render_out(const std::string& name) {
  const fs::path d = fs::path(::serosa::test_paths::binary_dir()) / "test-output" / "render" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

fs::path source(const std::string& rel) {
  return fs::path(::serosa::test_paths::source_dir()) / rel;
}

// The wound's look (render/materials.cpp: {0.45, 0.04, 0.06}; lit, with its wet highlight adding
// some white): green and blue below 0.45 of red. The tissues in these scenes keep green and blue
// above 0.55 of red under any lighting (shading scales colour; highlights add white); the tools
// are grey. (The liver, 0.36, would not be told apart this way: it is not in these scenes.)
bool wound_red(int r, int g, int b) { return r >= 40 && g * 20 < r * 9 && b * 20 < r * 9; }

// Pixels of `rgb` (3 or 4 channels per pixel) that look like the wound.
std::size_t wound_pixels(const std::vector<std::uint8_t>& px, int channels) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + static_cast<std::size_t>(channels) <= px.size();
       i += static_cast<std::size_t>(channels))
    if (wound_red(px[i], px[i + 1], px[i + 2])) ++n;
  return n;
}

// Pixels whose colour differs by more than 24 in some channel (RGBA images of one size).
std::size_t changed(const render::Image& a, const render::Image& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4)
    for (std::size_t k = 0; k < 3; ++k)
      if (std::abs(a.rgba[i + k] - b.rgba[i + k]) > 24) {
        ++n;
        break;
      }
  return n;
}

double coverage(const render::Image& img) {
  std::size_t n = 0;
  for (std::size_t i = 3; i < img.rgba.size(); i += 4) n += img.rgba[i] >= 128 ? 1 : 0;
  return static_cast<double>(n) / static_cast<double>(img.rgba.size() / 4);
}

// The appendectomy scene with every scripted tool on the transection path.
Scene transection_scene() {
  Scene scene = load_scene(source("config/transection.toml"));
  for (Tool& t : scene.tools)
    if (t.device.kind == DeviceKind::kScript)
      t.device.script = source("config/paths/appendix_transection.csv");
  return scene;
}

constexpr int kSteps = 30;  // the jaws close over steps 4..24

// Bright grey pixels: the instruments' steel and shafts (tissue is saturated pink or yellow).
std::size_t steel_pixels(const std::vector<std::uint8_t>& px, int channels) {
  std::size_t n = 0;
  for (std::size_t i = 0; i + static_cast<std::size_t>(channels) <= px.size();
       i += static_cast<std::size_t>(channels)) {
    const int r = px[i], g = px[i + 1], b = px[i + 2];
    if (r > 60 && std::abs(r - g) < 14 && std::abs(g - b) < 14) ++n;
  }
  return n;
}

constexpr std::array<View, 3> kViews{View::kVisual, View::kCollision, View::kMechanical};

// The scripted scissors transection of the appendix: the frame flags the faces the cut made (the
// wound), the tools are drawn once their devices posed them, and the pictures are written.
// Right after the cut the two faces of the wound touch (a closed slit); pulling the cut-off tip
// away, as the grasper does, shows the stump's wound in a close-up.
TEST(RenderWound, ScriptedAppendixCutFlagsTheWoundAndDrawsTheTools) {
  const fs::path dir = render_out("wound_appendix");
  const Scene scene = transection_scene();
  AssembledScene assembled = assemble_state(scene);
  Composition comp = compose(scene, assembled);
  ASSERT_NE(comp.cutting, nullptr);
  SimState& state = assembled.state;
  const std::size_t nodes_before = state.mesh.x.size();
  FramePictures pictures(dir, scene, state.mesh, assembled.group_names(),
                         {View::kVisual, View::kCollision, View::kMechanical});

  // Before any step no device has posed a tool: none drawn. After one step (the jaws still
  // open, nothing cut) the grasper and scissors are; the endoscope is a camera, never drawn.
  EXPECT_TRUE(pictures.frame(state).tools.empty());
  comp.runner->step(state);
  ASSERT_EQ(comp.cutting->stats().cuts, 0);
  const render::Image before = pictures.image(state, View::kVisual);
  pictures.take(state, "before");
  const render::RenderFrame& f0 = pictures.frame(state);
  EXPECT_EQ(f0.tools.size(), 2u);
  for (const auto c : f0.tri_cut) ASSERT_EQ(c, 0);
  EXPECT_GT(coverage(before), 0.05);
  EXPECT_EQ(wound_pixels(before.rgba, 4), 0u);
  EXPECT_GT(steel_pixels(before.rgba, 4), 500u);

  for (int i = 1; i < kSteps; ++i) comp.runner->step(state);
  ASSERT_GT(comp.cutting->stats().cuts, 0);
  const auto written = pictures.take(state, "after");
  ASSERT_EQ(written.size(), 3u);
  EXPECT_EQ(written[0].filename(), "after.png");
  EXPECT_EQ(written[1].filename(), "after_collision.png");
  EXPECT_EQ(written[2].filename(), "after_mechanical.png");
  for (const auto& p : written) EXPECT_GT(fs::file_size(p), 1000u) << p;
  std::size_t cut_faces = 0;
  for (const auto c : pictures.frame(state).tri_cut) cut_faces += c;
  RecordProperty("cut_faces", static_cast<int>(cut_faces));
  EXPECT_GT(cut_faces, 0u);

  // Traction, as the grasper gives it once the appendix is free: the cut-off tip (the smallest
  // piece) is pulled 10 mm away from the stump, and a close-up camera beside the gap, looking at
  // the stump, sees its wound.
  const std::vector<std::int32_t> piece = cutting::tet_components(state.mesh);
  const std::int32_t pieces = cutting::count_components(state.mesh);
  ASSERT_GE(pieces, 2);
  std::vector<std::int64_t> size(static_cast<std::size_t>(pieces), 0);
  for (const std::int32_t p : piece) ++size[static_cast<std::size_t>(p)];
  const auto tip =
      static_cast<std::int32_t>(std::min_element(size.begin(), size.end()) - size.begin());
  std::vector<std::uint8_t> on_tip(state.mesh.x.size(), 0);
  for (std::size_t t = 0; t < state.mesh.tets.size(); ++t)
    if (piece[t] == tip)
      for (const std::int32_t v : state.mesh.tets[t]) on_tip[static_cast<std::size_t>(v)] = 1;
  // The wound's centre: the nodes the cut added on the stump's side (cut points on the blade).
  Vec3 c_tip = Vec3::Zero(), c_wound = Vec3::Zero();
  double n_tip = 0.0, n_wound = 0.0;
  for (std::size_t v = 0; v < on_tip.size(); ++v) {
    if (on_tip[v] != 0) {
      c_tip += state.mesh.x[v];
      n_tip += 1.0;
    } else if (v >= nodes_before) {
      c_wound += state.mesh.x[v];
      n_wound += 1.0;
    }
  }
  ASSERT_GT(n_tip, 0.0);
  ASSERT_GT(n_wound, 0.0);
  c_tip /= n_tip;
  c_wound /= n_wound;
  const Vec3 away = (c_tip - c_wound).normalized();
  for (std::size_t v = 0; v < on_tip.size(); ++v)
    if (on_tip[v] != 0) state.mesh.x[v] += 0.010 * away;
  const Vec3 side = away.cross(Vec3(0.0, 1.0, 0.0)).normalized();
  const Vec3 eye = c_wound + 0.02 * away + 0.02 * side;
  render::Camera close_up;
  close_up.eye = {static_cast<float>(eye.x()), static_cast<float>(eye.y()),
                  static_cast<float>(eye.z())};
  close_up.target = {static_cast<float>(c_wound.x()), static_cast<float>(c_wound.y()),
                     static_cast<float>(c_wound.z())};
  close_up.fov_y_deg = 40.0f;
  pictures.set_camera(close_up);
  const render::Image pulled = pictures.image(state, View::kVisual);
  pictures.take(state, "pulled");
  const std::size_t wound = wound_pixels(pulled.rgba, 4);
  RecordProperty("wound_px", static_cast<int>(wound));
  const double px = static_cast<double>(pulled.width) * pulled.height;
  EXPECT_GT(static_cast<double>(wound), 0.01 * px) << "no wound colour in " << (dir / "pulled.png");
}

// A beam (config/beam.toml) cut right through by an oblique blade (cutting::cut_mesh, the same
// code the scissors call), its free end then moved 15 mm away: the clamped end's wound faces the
// camera. Wound pixels: none before, a clear patch after; the three views differ.
TEST(RenderWound, CutBeamShowsTheWoundInTheThreeViews) {
  const fs::path dir = render_out("wound_beam");
  const Scene scene = load_scene(source("config/beam.toml"));
  AssembledScene assembled = assemble_state(scene);
  SimState& state = assembled.state;
  FramePictures pictures(dir, scene, state.mesh, assembled.group_names(),
                         {View::kVisual, View::kCollision, View::kMechanical});
  std::array<render::Image, 3> before;
  for (std::size_t v = 0; v < kViews.size(); ++v) before[v] = pictures.image(state, kViews[v]);
  pictures.take(state, "before");
  EXPECT_EQ(wound_pixels(before[0].rgba, 4), 0u);
  EXPECT_GT(coverage(before[0]), 0.02);

  // The blade: a 60 mm square through the middle of the beam (0.05, 0, 0), its normal tilted
  // towards the camera (+z) and up (+y). It crosses the whole section: two pieces.
  const Vec3 c(0.05, 0.0, 0.0);
  const Vec3 n = Vec3(1.0, 0.6, 0.8).normalized();
  const Vec3 u = n.cross(Vec3(0.0, 0.0, 1.0)).normalized();
  const Vec3 w = n.cross(u).normalized();
  const double a = 0.03;
  const cutting::ConvexPolygon blade(
      {c + a * (u + w), c + a * (u - w), c - a * (u + w), c - a * (u - w)});
  cutting::CutResult cut = cutting::cut_mesh(state.mesh, blade);
  apply(state.mesh, cut.delta);
  ASSERT_EQ(cutting::count_components(state.mesh), 2);
  // Move the piece beyond the blade (the free end's component) 15 mm along the blade's normal.
  const std::vector<std::int32_t> piece = cutting::tet_components(state.mesh);
  std::int32_t free_piece = -1;
  for (std::size_t t = 0; t < state.mesh.tets.size() && free_piece < 0; ++t)
    for (const std::int32_t v : state.mesh.tets[t])
      if (state.mesh.rest[static_cast<std::size_t>(v)].x() > 0.099) free_piece = piece[t];
  ASSERT_GE(free_piece, 0);
  std::vector<std::uint8_t> moved(state.mesh.x.size(), 0);
  for (std::size_t t = 0; t < state.mesh.tets.size(); ++t)
    if (piece[t] == free_piece)
      for (const std::int32_t v : state.mesh.tets[t]) moved[static_cast<std::size_t>(v)] = 1;
  for (std::size_t v = 0; v < moved.size(); ++v)
    if (moved[v] != 0) state.mesh.x[v] += 0.015 * n;

  std::array<render::Image, 3> after;
  for (std::size_t v = 0; v < kViews.size(); ++v) after[v] = pictures.image(state, kViews[v]);
  pictures.take(state, "after");
  std::size_t cut_faces = 0;
  for (const auto f : pictures.frame(state).tri_cut) cut_faces += f;
  EXPECT_GT(cut_faces, 0u);
  const std::size_t wound = wound_pixels(after[0].rgba, 4);
  RecordProperty("wound_px", static_cast<int>(wound));
  const double px = static_cast<double>(after[0].width) * after[0].height;
  EXPECT_GT(static_cast<double>(wound), 0.002 * px) << "no wound colour in " << (dir / "after.png");
  // Only the visual view shows materials: the others have no wound colour.
  EXPECT_EQ(wound_pixels(after[1].rgba, 4), 0u);

  // The three views differ from each other in a good part of the picture.
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = i + 1; j < 3; ++j)
      EXPECT_GT(static_cast<double>(changed(after[i], after[j])), 0.01 * px)
          << "views " << i << " and " << j;
}

// `serosa headless --frames` draws the instruments (it drew the organs only before).
TEST(RenderWound, HeadlessFramesDrawTheTools) {
  const fs::path dir = render_out("headless_frames");
  HeadlessOptions o;
  o.scene = source("config/transection.toml");
  o.tool_path = source("config/paths/appendix_transection.csv");
  o.steps = 4;
  o.frames = dir;
  o.frame_count = 2;  // step 0 (no tool posed yet) and step 4 (jaws open, before the cut)
  o.progress = false;
  const auto report = run_headless(o);
  ASSERT_EQ(report["frames"].size(), 2u);
  std::array<std::size_t, 2> steel{};
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string png = report["frames"][k].get<std::string>();
    int w = 0, h = 0, n = 0;
    stbi_uc* data = stbi_load(png.c_str(), &w, &h, &n, 3);
    ASSERT_NE(data, nullptr) << png;
    const std::vector<std::uint8_t> rgb(data, data + static_cast<std::size_t>(w) * h * 3);
    stbi_image_free(data);
    steel[k] = steel_pixels(rgb, 3);
  }
  EXPECT_GT(steel[1], 500u);
  EXPECT_GT(steel[1], 5 * steel[0]);
}

}  // namespace
}  // namespace serosa::app
