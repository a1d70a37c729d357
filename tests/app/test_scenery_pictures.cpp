// The abdomen around the organs in the app's pictures: a scene with `[render] surroundings =
// "abdomen"` and a [[support]] gets its scenery (app/scenery_from_scene.h), and `serosa headless
// --frames` draws it, so that no single colour (the black void before) fills the picture.
// PNGs go to <build>/test-output/app/ for a person to look at.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "app/app_test_util.h"
#include "app/assemble_state.h"
#include "app/frame_pictures.h"
#include "app/read_png.h"
#include "app/scenery_from_scene.h"
#include "engine/scene/scene.h"
#include "render/image.h"
#include "render/image_stats.h"

namespace serosa::app {
namespace {

using testing::out_dir;
using testing::read_png;
using testing::source;

// Replaces every occurrence of `from` in `text` (there must be one).
void replace_all(std::string& text, const std::string& from, const std::string& to) {
  ASSERT_NE(text.find(from), std::string::npos) << from;
  std::string out;
  std::size_t done = 0;
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, done)) {
    out.append(text, done, at - done).append(to);
    done = at + from.size();
  }
  out.append(text, done, std::string::npos);
  text = std::move(out);
}

// A TOML string: `prefix` and the path, quoted. (Appended piece by piece: GCC 12 warns about
// operator+ on a literal and a temporary string, -Wrestrict.)
std::string quoted(const char* prefix, const std::filesystem::path& path) {
  std::string q = "\"";
  q.append(prefix).append(path.string()).append("\"");
  return q;
}

// config/appendectomy.toml (the default scene: the posterior wall under the organs as a support)
// written into `dir` with its files named by absolute paths and the given surroundings.
std::filesystem::path abdomen_scene(const std::filesystem::path& dir,
                                    const std::string& surroundings) {
  std::ifstream in(source("config/appendectomy.toml"));
  std::stringstream buf;
  buf << in.rdbuf();
  std::string toml = buf.str();
  replace_all(toml, "\"../assets/appendectomy_procedure.msh\"",
              quoted("", source("assets/appendectomy_procedure.msh")));
  replace_all(toml, "\"script:paths/appendectomy_procedure.csv\"",
              quoted("script:", source("config/paths/appendectomy_procedure.csv")));
  replace_all(toml, "\"assessment/procedure.toml\"",
              quoted("", source("config/assessment/procedure.toml")));
  std::string chosen = "surroundings = ";
  chosen.append(quoted("", surroundings));
  replace_all(toml, "surroundings = \"abdomen\"", chosen);
  const std::filesystem::path file = dir / ("appendectomy_" + surroundings + ".toml");
  std::ofstream(file) << toml;
  return file;
}

// The scene's scenery: an abdomen on the support around the organs, the same every time it is
// built; none when the scene asks for none.
TEST(SceneryFromScene, AbdomenOnTheSupportOnlyWhenAsked) {
  const std::filesystem::path dir = out_dir("scenery_from_scene");
  const Scene scene = load_scene(abdomen_scene(dir, "abdomen"));
  ASSERT_EQ(scene.render.surroundings, Surroundings::kAbdomen);
  ASSERT_EQ(scene.supports.size(), 1u);
  const AssembledScene assembled = assemble_state(scene);
  const render::Scenery s = scenery_from_scene(scene, assembled.state.mesh);
  ASSERT_FALSE(s.empty());
  EXPECT_NE(s.version, 0u);
  EXPECT_EQ(scenery_from_scene(scene, assembled.state.mesh).version, s.version);
  // Nothing under the organs (the rest box's footprint) rises above the support plane.
  Vec3 lo = assembled.state.mesh.rest.front(), hi = lo;
  for (const Vec3& p : assembled.state.mesh.rest) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  std::size_t under = 0;
  for (std::size_t i = 0; i < s.num_vertices(); ++i) {
    const double x = s.pos[3 * i], y = s.pos[3 * i + 1], z = s.pos[3 * i + 2];
    if (x < lo.x() || x > hi.x() || y < lo.y() || y > hi.y()) continue;
    ++under;
    EXPECT_LE(z, -0.0036 + 1e-6) << "vertex " << i;
  }
  EXPECT_GT(under, 100u);

  const Scene none = load_scene(abdomen_scene(dir, "none"));
  EXPECT_TRUE(scenery_from_scene(none, assembled.state.mesh).empty());
}

// `serosa headless --frames` on the appendectomy with an abdomen: the last picture has no colour
// over a fifth of it. Without the abdomen the same view is mostly the black void.
TEST(SceneryHeadless, PicturesShowTheAbdomen) {
  const std::filesystem::path dir = out_dir("scenery_pictures");
  const std::filesystem::path scene = abdomen_scene(dir, "abdomen");
  const auto run = testing::run_serosa("headless " + shell_quote(scene.string()) +
                                       " --steps 10 --frame-count 2 --frames " +
                                       shell_quote((dir / "abdomen").string()));
  ASSERT_EQ(run.code, 0) << run.out;
  if (run.out.find("'supports' is not implemented") != std::string::npos)
    std::printf("note: effect 'supports' is not simulated in this build\n");
  const render::Image last = read_png(dir / "abdomen" / "step_000010.png");
  ASSERT_GT(last.width, 0) << run.out;
  const render::DominantColor with = render::most_common_color(last);
  EXPECT_LT(with.fraction, 0.2);

  // The same first picture without surroundings, drawn in process.
  const Scene bare = load_scene(abdomen_scene(dir, "none"));
  AssembledScene assembled = assemble_state(bare);
  FramePictures pictures(dir / "none", bare, assembled.state.mesh, assembled.group_names());
  // The void: pixels nothing covers (alpha 0; the optic's vignette shades their colour).
  const render::Image image =
      pictures.image(assembled.state, render::SnapshotOptions::View::kVisual);
  std::size_t void_px = 0;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) void_px += image.rgba[i] == 0 ? 1 : 0;
  const double without = static_cast<double>(void_px) / (image.rgba.size() / 4.0);
  EXPECT_GT(without, 0.5);
  std::printf("most common colour with the abdomen %.3f; the void without it %.3f\n", with.fraction,
              without);
}

}  // namespace
}  // namespace serosa::app
