// The assessment rubric (engine/scene/rubric.h): the shipped one loads and scores every GOALS
// domain; every mistake an instructor can make in one is an InputError naming the rubric file, the
// line and the key; and a scene whose rubric names what the scene does not have is refused at load.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/input_error.h"
#include "engine/scene/rubric.h"
#include "engine/scene/scene.h"
#include "support/test_paths.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

class RubricTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("serosa_rubric_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  fs::path write(const std::string& rel, const std::string& text) const {
    std::ofstream(m_dir / rel) << text;
    return m_dir / rel;
  }

  // One metric per domain, the first one's lines given: a valid rubric when `first` is.
  static std::string rubric(const std::string& first) {
    std::string s = "title = \"t\"\npass_score = 75\n" + first;
    for (const char* d : {"bimanual_dexterity", "efficiency", "tissue_handling", "autonomy"})
      s.append("[[metric]]\nname = \"time_s\"\ndomain = \"")
          .append(d)
          .append("\"\ngood = 1\npoor = 2\n");
    return s;
  }

  // Expects an InputError from the rubric file at `line` whose message holds `needle`.
  void expect_error(const std::string& text, std::int64_t line, const std::string& needle) const {
    const fs::path f = write("r.toml", text);
    try {
      (void)load_rubric(f);
      ADD_FAILURE() << "no error; expected '" << needle << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), f.string()) << e.what();
      EXPECT_EQ(e.line(), line) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  }

  fs::path m_dir;
};

const std::string kDepth =
    "[[metric]]\nname = \"cut.deviation_max_m\"\ndomain = \"depth_perception\"\n"
    "unit = \"m\"\ngood = 0.002\npoor = 0.008\n";

TEST_F(RubricTest, TheShippedRubricScoresEveryDomain) {
  const Rubric r =
      load_rubric(fs::path(test_paths::source_dir()) / "config/assessment/appendectomy.toml");
  EXPECT_FALSE(r.title.empty());
  EXPECT_GT(r.pass_score, 0.0);
  for (const std::string_view d : kGoalsDomains) {
    int n = 0;
    for (const RubricMetric& m : r.metrics) n += m.domain == d ? 1 : 0;
    EXPECT_GT(n, 0) << d;
  }
  for (const RubricMetric& m : r.metrics) {
    EXPECT_GE(m.limit, std::min(m.good, m.poor)) << m.name;
    EXPECT_LE(m.limit, std::max(m.good, m.poor)) << m.name;
    EXPECT_GT(m.line, 0) << m.name;
  }
}

TEST_F(RubricTest, DefaultsAndEveryKeyRead) {
  const Rubric r = load_rubric(write("r.toml", rubric(kDepth + "limit = 0.003\nweight = 2\n"
                                                               "critical = true\n")));
  ASSERT_EQ(r.metrics.size(), 5u);
  EXPECT_EQ(r.pass_score, 75.0);
  EXPECT_EQ(r.metrics[0].name, "cut.deviation_max_m");
  EXPECT_EQ(r.metrics[0].limit, 0.003);
  EXPECT_EQ(r.metrics[0].weight, 2.0);
  EXPECT_TRUE(r.metrics[0].critical);
  EXPECT_EQ(r.metrics[1].limit, 1.5);  // halfway by default
  EXPECT_FALSE(r.metrics[1].critical);
}

// A task that does not exercise every domain scores only those it does.
TEST_F(RubricTest, ARubricMayScoreSomeDomainsOnly) {
  const Rubric r = load_rubric(write("r.toml", kDepth));
  ASSERT_EQ(r.metrics.size(), 1u);
  EXPECT_EQ(r.metrics[0].domain, "depth_perception");
}

TEST_F(RubricTest, MistakesNameTheFileTheLineAndTheKey) {
  expect_error(rubric(kDepth + "goood = 1\n"), 9, "metric[0].goood: unknown key");
  expect_error(rubric("[[metric]]\nname = \"time_s\"\ndomain = \"speed\"\ngood = 1\npoor = 2\n"), 5,
               "metric[0].domain: unknown domain 'speed'");
  expect_error(rubric("[[metric]]\nname = \"lap_time\"\ndomain = \"depth_perception\"\n"
                      "good = 1\npoor = 2\n"),
               4, "no metric named 'lap_time'");
  expect_error(rubric("[[metric]]\nname = \"time_s\"\ndomain = \"depth_perception\"\n"
                      "good = 1\npoor = 1\n"),
               7, "metric[0].poor: equal to good");
  expect_error(rubric(kDepth + "limit = 0.01\n"), 9, "metric[0].limit: outside [good, poor]");
  expect_error(rubric(kDepth + "weight = 0\n"), 9, "metric[0].weight: not positive");
  expect_error(rubric(kDepth + "critical = \"yes\"\n"), 9, "metric[0].critical: not a boolean");
  expect_error(rubric(kDepth + "good = \"x\"\n"), 9, "TOML syntax error");  // a duplicate key
  expect_error("pass_score = 120\n" + kDepth, 1, "pass_score: out of range");
  expect_error("title = \"t\"\n", 0, "no [[metric]] tables");
  expect_error(rubric("[[metric]]\ndomain = \"depth_perception\"\ngood = 1\npoor = 2\n"), 3,
               "metric[0]: missing key 'name'");
  try {
    (void)load_rubric(m_dir / "absent.toml");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such rubric file"), std::string::npos) << e.what();
  }
}

// The scene checks the rubric against itself: tools, groups, effects and the planned cut.
TEST_F(RubricTest, ASceneRefusesARubricNamingWhatItLacks) {
  write("organ.msh", "$MeshFormat\n");
  write("p.csv", "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n0,g,0,0,0,1,0,0,0,0\n0,s,0,0,0,1,0,0,0,0\n");
  const std::string scene_head =
      "[scene]\neffects = [\"fem\", \"surface\", \"contact\", \"cutting\"]\n"
      "[[organ]]\nname = \"o\"\nmesh = \"organ.msh\"\ngroups = { 1 = \"appendix\" }\n"
      "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"script:p.csv\"\n"
      "[[tool]]\nname = \"s\"\nkind = \"scissors\"\ndevice = \"script:p.csv\"\n";
  const auto scene_with = [&](const std::string& metric, bool planned) {
    write("r.toml", rubric(metric));
    return scene_head + "[metrics]\n" +
           (planned ? "planned_cut = [[0, 0, 0], [0.01, 0, 0]]\n" : "") + "rubric = \"r.toml\"\n";
  };
  const auto metric = [](const std::string& name) {
    return "[[metric]]\nname = \"" + name +
           "\"\ndomain = \"depth_perception\"\ngood = 1\npoor = 2\n";
  };
  // Accepted: every kind of name, with what it needs.
  for (const char* ok : {"path_length_m.g", "force_max_n.s", "pieces.appendix", "bimanual_fraction",
                         "force_over_s", "cut.collateral_m3"}) {
    const Scene s = parse_scene_text(scene_with(metric(ok), true), m_dir / "scene.toml");
    ASSERT_TRUE(s.metrics.rubric.has_value()) << ok;
    EXPECT_EQ(s.metrics.rubric->metrics[0].name, ok);
  }
  const auto refused = [&](const std::string& toml, const std::string& needle) {
    try {
      (void)parse_scene_text(toml, m_dir / "scene.toml");
      ADD_FAILURE() << "accepted; expected '" << needle << "'";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("metrics.rubric: the rubric's metric"), std::string::npos) << what;
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_GT(e.line(), 0) << what;
    }
  };
  refused(scene_with(metric("path_length_m.hook"), true), "names no tool of this scene");
  refused(scene_with(metric("pieces.colon"), true), "names no group of this scene");
  refused(scene_with(metric("cut.deviation_max_m"), false), "needs a planned cut");
  std::string no_contact = scene_with(metric("force_max_n.g"), true);
  no_contact.replace(no_contact.find(", \"contact\""), 11, "");
  refused(no_contact, "needs effect \"contact\"");
  // What the endoscope saw needs an endoscope, and targets to look at.
  refused(scene_with(metric("out_of_view_s"), true), "needs an endoscope");
  refused(scene_with(metric("targets_missed"), true), "needs an endoscope");
  write("q.csv", "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n0,e,0,0,0,1,0,0,0,0\n");
  const std::string with_scope =
      "[[tool]]\nname = \"e\"\nkind = \"endoscope\"\n"
      "device = \"script:q.csv\"\n";
  refused(with_scope + scene_with(metric("targets_time_s"), true), "needs targets to look at");
  refused(with_scope + scene_with(metric("out_of_view_s.hook"), true), "names no tool");
  const std::string targets = with_scope + scene_with(metric("targets_missed"), true);
  const Scene seen =
      parse_scene_text(std::string(targets).replace(targets.find("[metrics]\n"), 10,
                                                    "[metrics]\nview_targets = [[0, 0, 0.01]]\n"),
                       m_dir / "scene.toml");
  EXPECT_EQ(seen.metrics.view_targets_m.size(), 1u);
}

// The curriculum's families: a step's time and path need the procedure's steps and a step's name;
// the clips need the clips' effect, an artery, and for the target error a target; the transfer's
// values need a transfer. A transfer names a group of the scene and a radius > 0.
TEST_F(RubricTest, TaskMetricsNeedWhatTheyMeasure) {
  write("organ.msh", "$MeshFormat\n");
  write("p.csv", "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n0,g,0,0,0,1,0,0,0,0\n0,c,0,0,0,1,0,0,0,0\n");
  const auto scene = [&](const std::string& name, const std::string& metrics,
                         const std::string& effects = "\"clips\", ") {
    write("r.toml", rubric("[[metric]]\nname = \"" + name +
                           "\"\ndomain = \"depth_perception\"\ngood = 1\npoor = 2\n"));
    return "[scene]\neffects = [\"fem\", \"surface\", " + effects +
           "\"contact\"]\n[[organ]]\nname = \"o\"\nmesh = \"organ.msh\"\n"
           "groups = { 1 = \"appendix\", 2 = \"cecum\", 3 = \"fold\", 4 = \"artery\" }\n"
           "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"script:p.csv\"\n"
           "[[tool]]\nname = \"c\"\nkind = \"clip-applier\"\ndevice = \"script:p.csv\"\n"
           "[metrics]\n" +
           metrics + "rubric = \"r.toml\"\n";
  };
  const std::string steps =
      "artery = \"artery\"\nprocedure = { specimen = \"appendix\", base = \"cecum\", "
      "mesentery = \"fold\" }\n";
  const std::string transfer = "transfer = { object = \"appendix\", target = [0, 0, 0] }\n";
  const auto accepted = [&](const std::string& toml) {
    EXPECT_NO_THROW((void)parse_scene_text(toml, m_dir / "scene.toml")) << toml;
  };
  accepted(scene("step_time_s.divide_mesentery", steps));
  accepted(scene("step_path_length_m.extract", steps));
  accepted(scene("clips_on_artery", "artery = \"artery\"\n"));
  accepted(scene("clip_target_error_m", "artery = \"artery\"\nclip_target = [0, 0, 0]\n"));
  accepted(scene("transfer.placed", transfer));
  const auto refused = [&](const std::string& toml, const std::string& needle) {
    try {
      (void)parse_scene_text(toml, m_dir / "scene.toml");
      ADD_FAILURE() << "accepted; expected '" << needle << "'";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_GT(e.line(), 0) << e.what();
    }
  };
  refused(scene("step_time_s.expose", ""), "needs the procedure's steps followed");
  refused(scene("step_time_s.suture", steps), "names no step of the procedure");
  refused(scene("clips_off_artery", ""), "needs an artery to watch");
  std::string no_clips = scene("clips_on_artery", "artery = \"artery\"\n", "");
  const std::string applier = "[[tool]]\nname = \"c\"\nkind = \"clip-applier\"";
  no_clips.replace(no_clips.find(applier), applier.size(),
                   "[[tool]]\nname = \"c\"\nkind = \"grasper\"");
  refused(no_clips, "needs effect \"clips\"");
  refused(scene("clip_target_error_m", "artery = \"artery\"\n"), "needs where the clip should go");
  refused(scene("transfer.drops", ""), "needs a transfer to follow");
  refused(scene("tears", ""), "needs the stress at which tissue tears");
  accepted(scene("tears", "tear_stress = 1e6\n"));
  refused(scene("time_s", "tear_stress = -1\n"), "metrics.tear_stress");
  refused(scene("time_s", "clip_target = [0, 0, 0]\n"), "no artery is named");
  refused(scene("time_s", "transfer = { object = \"bead\", target = [0, 0, 0] }\n"), "bead");
  refused(scene("time_s", "transfer = { object = \"appendix\", target = [0, 0, 0], radius = 0 }\n"),
          "metrics.transfer.radius");
  refused(scene("time_s", "transfer = { object = \"appendix\", target = [0, 0] }\n"),
          "metrics.transfer.target");
  refused(scene("time_s", "transfer = { object = \"appendix\", target = [0, 0, 0], size = 1 }\n"),
          "metrics.transfer.size: unknown key");
}

}  // namespace
}  // namespace serosa
