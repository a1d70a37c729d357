// The [metrics] table of a scene: the planned cut line and its tolerance band.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/input_error.h"
#include "engine/scene/scene.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

class SceneMetrics : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() / ("serosa_scene_metrics_" + std::to_string(::getpid()));
    fs::create_directories(m_dir);
    std::ofstream(m_dir / "organ.msh") << "$MeshFormat\n";
  }
  void TearDown() override { fs::remove_all(m_dir); }
  Scene parse(const std::string& extra) {
    return parse_scene_text("[[organ]]\nname = \"a\"\nmesh = \"organ.msh\"\n" + extra,
                            m_dir / "scene.toml");
  }
  fs::path m_dir;
};

TEST_F(SceneMetrics, DefaultsToNoPlannedCut) {
  const Scene s = parse("");
  EXPECT_TRUE(s.metrics.planned_cut_m.empty());
  EXPECT_DOUBLE_EQ(s.metrics.cut_band_m, 0.003);
}

TEST_F(SceneMetrics, ReadsPolylineAndBand) {
  const Scene s = parse(
      "[metrics]\nplanned_cut = [[0, 0, 0], [0.01, 0, 0], [0.01, 0.02, 0]]\n"
      "cut_band = 0.002\n");
  ASSERT_EQ(s.metrics.planned_cut_m.size(), 3u);
  EXPECT_EQ(s.metrics.planned_cut_m[2], Vec3(0.01, 0.02, 0));
  EXPECT_DOUBLE_EQ(s.metrics.cut_band_m, 0.002);
}

TEST_F(SceneMetrics, BadValuesNameTheKeyAndLine) {
  for (const std::string bad :
       {"[metrics]\nplanned_cut = [[0, 0, 0]]\n", "[metrics]\nplanned_cut = [[0, 0, 0], [1, 1]]\n",
        "[metrics]\ncut_band = 0\n", "[metrics]\nband = 1\n"}) {
    try {
      (void)parse(bad);
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("metrics"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(":5"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace serosa
