// Overrides of scene keys as an engineer types them on the command line
// (engine/scene/scene_override.h): a bare word sets a key that holds text, a key through a list of
// tables is told to name one by its index, and what is not TOML where a number belongs stays an
// error naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "engine/input_error.h"
#include "engine/scene/scene_override.h"
#include "support/test_paths.h"

namespace serosa {
namespace {

std::filesystem::path beam() {
  return std::filesystem::path(test_paths::source_dir()) / "config" / "beam.toml";
}

std::string error_of(const std::vector<SceneOverride>& o) {
  try {
    (void)load_scene(beam(), o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneOverride, ABareWordSetsAKeyThatHoldsText) {
  for (const auto& [word, kind] :
       {std::pair{"cholmod", SolverKind::kCholmod}, std::pair{"pcg", SolverKind::kPcg},
        std::pair{"pcg-lagged", SolverKind::kPcgLagged}}) {
    std::string text = "\"";
    text.append(word).append("\"");
    const Scene quoted = load_scene(beam(), {{"solver.kind", text}});
    const Scene bare = load_scene(beam(), {{"solver.kind", word}});
    EXPECT_EQ(bare.solver.kind, kind) << word;
    EXPECT_EQ(quoted.solver.kind, kind) << word;
  }
  // A word that is no solver is the loader's error, naming the key, as a quoted one is.
  EXPECT_NE(error_of({{"solver.kind", "choldom"}}).find("solver.kind"), std::string::npos);
}

TEST(SceneOverride, ABareWordWhereANumberBelongsIsNotTOML) {
  const std::string e = error_of({{"scene.dt", "small"}});
  EXPECT_NE(e.find("scene.dt: the value small is not TOML"), std::string::npos) << e;
  // Where the file does not set the key, the word is text, and the loader says it is no number.
  const std::string absent = error_of({{"solver.tolerance", "small"}});
  EXPECT_NE(absent.find("solver.tolerance: expected a number, got a string"), std::string::npos)
      << absent;
  // Text with spaces or quotes inside is never taken as a bare word.
  EXPECT_NE(error_of({{"solver.kind", "pcg lagged"}}).find("is not TOML"), std::string::npos);
}

TEST(SceneOverride, AKeyThroughAListOfTablesIsToldToNameOneByIndex) {
  const std::string e = error_of({{"organ.young", "5e3"}});
  EXPECT_NE(e.find("organ is a list of [[organ]] tables"), std::string::npos) << e;
  EXPECT_NE(e.find("organ.0.young"), std::string::npos) << e;
  const Scene s = load_scene(beam(), {{"organ.0.young", "5e3"}});
  EXPECT_EQ(s.organs[0].material.young_pa, 5e3);
}

}  // namespace
}  // namespace serosa
