// Scene loading: defaults, every key, relative paths, presets, and one test per error kind, each
// checking that the message names the key path and the line.
#include "engine/scene/scene.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>

#include "engine/input_error.h"
#include "engine/scene/presets.h"
#include "support/test_paths.h"

namespace serosa {
namespace {

namespace fs = std::filesystem;

const std::string kCsvHeader = "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n";

// Lines 1-3 of most test scenes.
const std::string kOrgan =
    "[[organ]]\n"
    "name = \"appendix\"\n"
    "mesh = \"organ.msh\"\n";

class SceneTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("serosa_scene_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir / "paths");
    write("organ.msh", "$MeshFormat\n");  // only its existence matters to the scene loader
    write("colon.msh", "$MeshFormat\n");
    write("paths/p.csv", kCsvHeader +
                             "0,grasper,0,0,0,1,0,0,0,0\n"
                             "0,scissors,0,0,0,1,0,0,0,0\n"
                             "1,grasper,0.01,0,0,1,0,0,0,0.5\n");
  }
  void TearDown() override { fs::remove_all(m_dir); }

  void write(const std::string& rel, const std::string& text) const {
    std::ofstream(m_dir / rel) << text;
  }
  [[nodiscard]] fs::path scene_path() const { return m_dir / "scene.toml"; }
  [[nodiscard]] Scene parse(const std::string& toml) const {
    return parse_scene_text(toml, scene_path());
  }

  // Expects an InputError at `line` naming `key` (the key path) and containing `needle`.
  void expect_error(const std::string& toml, std::int64_t line, const std::string& key,
                    const std::string& needle = {}) const {
    try {
      (void)parse(toml);
      ADD_FAILURE() << "no error; expected one at line " << line << " for " << key;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.file(), scene_path().string()) << what;
      EXPECT_EQ(e.line(), line) << what;
      if (line > 0) {
        EXPECT_NE(what.find(scene_path().string() + ":" + std::to_string(line) + ": "),
                  std::string::npos)
            << what;
      }
      EXPECT_EQ(e.message().rfind(key + ": ", 0), 0u)
          << "message should start with the key path '" << key << "': " << what;
      EXPECT_NE(what.find(needle), std::string::npos) << "missing '" << needle << "': " << what;
    }
  }

  fs::path m_dir;
};

// ---------------------------------------------------------------------------------------------
// Names

TEST(SceneNames, EffectsRoundTrip) {
  for (const Effect e : kAllEffects) {
    EXPECT_EQ(effect_from_name(effect_name(e)), e);
  }
  EXPECT_EQ(effect_name(Effect::kContact), "contact");
  EXPECT_FALSE(effect_from_name("Fem").has_value());
  EXPECT_FALSE(effect_from_name("").has_value());
}

TEST(SceneNames, EnumsRoundTrip) {
  for (const auto q : {Quality::kFast, Quality::kBalanced, Quality::kAccurate}) {
    EXPECT_EQ(quality_from_name(quality_name(q)), q);
  }
  for (const auto k : {SolverKind::kPcg, SolverKind::kCholmod, SolverKind::kPcgCholmod}) {
    EXPECT_EQ(solver_kind_from_name(solver_kind_name(k)), k);
  }
  for (const auto k : {ToolKind::kScissors, ToolKind::kGrasper, ToolKind::kEndoscope,
                       ToolKind::kClipApplier, ToolKind::kHook}) {
    EXPECT_EQ(tool_kind_from_name(tool_kind_name(k)), k);
  }
  for (const auto k : {DeviceKind::kRig, DeviceKind::kRigEmulated, DeviceKind::kMouse}) {
    EXPECT_EQ(device_kind_from_name(device_kind_name(k)), k);
  }
  for (const auto m : {CutMethod::kPattern, CutMethod::kRemove, CutMethod::kSnap}) {
    EXPECT_EQ(cut_method_from_name(cut_method_name(m)), m);
  }
  EXPECT_EQ(solver_kind_name(SolverKind::kPcgCholmod), "pcg-cholmod");
  EXPECT_EQ(device_kind_name(DeviceKind::kRigEmulated), "rig-emulated");
  EXPECT_EQ(hand_from_name("left"), Hand::kLeft);
}

// ---------------------------------------------------------------------------------------------
// Valid scenes

TEST_F(SceneTest, MinimalSceneGetsDefaults) {
  const Scene s = parse(kOrgan);
  EXPECT_DOUBLE_EQ(s.settings.dt_s, 0.005);
  EXPECT_EQ(s.settings.gravity_mps2, Vec3(0.0, -9.81, 0.0));
  EXPECT_EQ(s.settings.effects, (std::set<Effect>{Effect::kFem, Effect::kGravity}));
  EXPECT_FALSE(s.settings.quality.has_value());
  ASSERT_EQ(s.organs.size(), 1u);
  const Organ& o = s.organs[0];
  EXPECT_EQ(o.name, "appendix");
  EXPECT_EQ(o.mesh, m_dir / "organ.msh");
  EXPECT_TRUE(o.groups.empty());
  EXPECT_DOUBLE_EQ(o.material.young_pa, 5.0e3);
  EXPECT_DOUBLE_EQ(o.material.poisson, 0.45);
  EXPECT_DOUBLE_EQ(o.material.density_kgpm3, 1.05e3);
  EXPECT_DOUBLE_EQ(o.material.damping.mass_per_s, 0.1);
  EXPECT_DOUBLE_EQ(o.material.damping.stiffness_s, 0.01);
  EXPECT_DOUBLE_EQ(o.material.plasticity.yield, 0.05);
  EXPECT_TRUE(o.group_materials.empty());
  EXPECT_TRUE(o.fixed.empty());
  EXPECT_TRUE(o.transform.is_identity());
  EXPECT_EQ(s.solver.kind, SolverKind::kPcgLagged);  // scene_default_solver()
  EXPECT_DOUBLE_EQ(s.solver.tolerance, 1e-3);
  EXPECT_EQ(s.solver.max_iterations, 200);
  EXPECT_EQ(s.render.tessellation, 3);
  EXPECT_DOUBLE_EQ(s.render.shape_factor, 0.75);
  EXPECT_EQ(s.render.width, 1280);
  EXPECT_EQ(s.render.height, 720);
  EXPECT_TRUE(s.tools.empty());
  EXPECT_FALSE(s.record.path.has_value());
  EXPECT_EQ(s.record.hash_every, 100);
  EXPECT_DOUBLE_EQ(s.record.snapshot_every_s, 1.0);
  EXPECT_TRUE(s.solver.patch_after_cut);
  EXPECT_EQ(s.cutting.method, CutMethod::kPattern);
  EXPECT_EQ(s.cutting.strokes, StrokeSurfaceKind::kSwept);
  EXPECT_DOUBLE_EQ(s.cutting.tolerance, 1e-3);
  EXPECT_EQ(s.headless.steps, 1000);
  EXPECT_EQ(s.file, scene_path());
}

TEST_F(SceneTest, ReadsEveryKey) {
  const Scene s = parse(R"(
[scene]
dt = 0.002
gravity = [0, 0, -9.81]
effects = ["record", "fem", "gravity", "supports", "plasticity", "cutting", "clips", "loops", "cautery", "surface", "contact", "render", "haptics", "bleeding", "smoke"]

[[support]]
name = "posterior wall"
point = [0, 0, -0.004]
normal = [0, 0, 3]

[[organ]]
name = "appendix"
mesh = "organ.msh"
groups = { 1 = "appendix", 2 = "mesoappendix", 3 = "cecum" }
young = 3000
poisson = 0.4
density = 1000.0
damping = { mass = 0.2, stiffness = 0.05 }
plasticity = { yield = 0.1, creep = 2.0, max = 0.4 }
fixed = { box = [[-1, -1, -1], [1, 0, 1]], groups = ["cecum", 2], nodes = [7, 3, 7] }
transform = { translate = [0.1, 0, 0], rotate_deg = [0, 0, 90], scale = 0.001 }
[organ.material.mesoappendix]
young = 1500
[organ.material.3]
poisson = 0.3
damping = { mass = 0.0 }

[[organ]]
name = "colon"
mesh = "colon.msh"
groups = { 4 = "colon" }

[solver]
kind = "pcg-cholmod"
tolerance = 1e-5
max_iterations = 50
after_cut = "factor"
urgent_lag_steps = 7
cut_lag_steps = 30
patch_rings = 3

[render]
tessellation = 5
shape_factor = 0.5
width = 640
height = 480
surroundings = "abdomen"
looks = { mesoappendix = "fat", colon = "cecum" }

[[tool]]
name = "grasper"
kind = "grasper"
device = "script:paths/p.csv"
hand = "left"
trocar = [0.05, 0.1, 0.0]

[[tool]]
name = "scissors"
kind = "scissors"
device = "rig"
hand = "right"

[[tool]]
name = "camera"
kind = "endoscope"
device = "mouse"

[record]
path = "out/run.lapr"
hash_every = 10
snapshot_every_s = 0.5

[cutting]
method = "snap"
tolerance = 0.05
strokes = "plane"

[metrics]
artery = "mesoappendix"

[headless]
steps = 250
)");
  EXPECT_DOUBLE_EQ(s.settings.dt_s, 0.002);
  EXPECT_EQ(s.settings.gravity_mps2, Vec3(0, 0, -9.81));
  EXPECT_EQ(s.settings.effects.size(), kNumEffects);
  ASSERT_EQ(s.supports.size(), 1u);
  EXPECT_EQ(s.supports[0].name, "posterior wall");
  EXPECT_EQ(s.supports[0].point_m, Vec3(0, 0, -0.004));
  EXPECT_EQ(s.supports[0].normal, Vec3(0, 0, 1));
  EXPECT_EQ(s.render.surroundings, Surroundings::kAbdomen);
  EXPECT_EQ(s.render.looks,
            (std::map<std::string, std::string>{{"mesoappendix", "fat"}, {"colon", "cecum"}}));
  ASSERT_EQ(s.organs.size(), 2u);
  const Organ& o = s.organs[0];
  EXPECT_EQ(o.groups.at(2), "mesoappendix");
  EXPECT_EQ(o.group_id("cecum"), 3);
  EXPECT_DOUBLE_EQ(o.material.young_pa, 3000.0);
  EXPECT_DOUBLE_EQ(o.material.poisson, 0.4);
  EXPECT_DOUBLE_EQ(o.material.density_kgpm3, 1000.0);
  EXPECT_DOUBLE_EQ(o.material.damping.mass_per_s, 0.2);
  EXPECT_DOUBLE_EQ(o.material.damping.stiffness_s, 0.05);
  EXPECT_DOUBLE_EQ(o.material.plasticity.creep_per_s, 2.0);
  // Overrides inherit the organ's values for keys they do not set.
  EXPECT_DOUBLE_EQ(o.material_for(2).young_pa, 1500.0);
  EXPECT_DOUBLE_EQ(o.material_for(2).poisson, 0.4);
  EXPECT_DOUBLE_EQ(o.material_for(3).young_pa, 3000.0);
  EXPECT_DOUBLE_EQ(o.material_for(3).poisson, 0.3);
  EXPECT_DOUBLE_EQ(o.material_for(3).damping.mass_per_s, 0.0);
  EXPECT_DOUBLE_EQ(o.material_for(3).damping.stiffness_s, 0.05);
  EXPECT_DOUBLE_EQ(o.material_for(1).young_pa, 3000.0);
  ASSERT_TRUE(o.fixed.box.has_value());
  EXPECT_EQ(o.fixed.box->max_m, Vec3(1, 0, 1));
  EXPECT_TRUE(o.fixed.box->contains(Vec3(0, -0.5, 0)));
  EXPECT_FALSE(o.fixed.box->contains(Vec3(0, 0.5, 0)));
  EXPECT_EQ(o.fixed.groups, (std::vector<int>{2, 3}));
  EXPECT_EQ(o.fixed.nodes, (std::vector<std::int32_t>{3, 7}));
  EXPECT_FALSE(o.transform.is_identity());
  const Vec3 p = o.transform.apply(Vec3(1000, 0, 0));  // 1 m in mm, rotated to +y, moved +x
  EXPECT_NEAR((p - Vec3(0.1, 1.0, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(s.organs[1].groups.at(4), "colon");
  EXPECT_EQ(s.solver.kind, SolverKind::kPcgCholmod);
  EXPECT_DOUBLE_EQ(s.solver.tolerance, 1e-5);
  EXPECT_EQ(s.solver.max_iterations, 50);
  EXPECT_EQ(s.render.tessellation, 5);
  EXPECT_DOUBLE_EQ(s.render.shape_factor, 0.5);
  EXPECT_EQ(s.render.width, 640);
  EXPECT_EQ(s.render.height, 480);
  ASSERT_EQ(s.tools.size(), 3u);
  EXPECT_EQ(s.tools[0].kind, ToolKind::kGrasper);
  EXPECT_EQ(s.tools[0].device.kind, DeviceKind::kScript);
  EXPECT_EQ(s.tools[0].device.script, m_dir / "paths" / "p.csv");
  EXPECT_EQ(s.tools[0].hand, Hand::kLeft);
  EXPECT_EQ(s.tools[0].trocar_m, Vec3(0.05, 0.1, 0.0));
  EXPECT_EQ(s.tools[1].device.kind, DeviceKind::kRig);
  EXPECT_FALSE(s.tools[1].trocar_m.has_value());
  EXPECT_EQ(s.tools[2].kind, ToolKind::kEndoscope);
  EXPECT_EQ(s.tools[2].device.kind, DeviceKind::kMouse);
  EXPECT_FALSE(s.tools[2].hand.has_value());
  EXPECT_EQ(s.tool_index("camera"), 2u);
  EXPECT_FALSE(s.tool_index("hook").has_value());
  EXPECT_EQ(s.record.path, m_dir / "out" / "run.lapr");
  EXPECT_EQ(s.record.hash_every, 10);
  EXPECT_DOUBLE_EQ(s.record.snapshot_every_s, 0.5);
  EXPECT_FALSE(s.solver.patch_after_cut);
  EXPECT_EQ(s.solver.urgent_lag_steps, 7);
  EXPECT_EQ(s.solver.cut_lag_steps, 30);
  EXPECT_EQ(s.solver.patch_rings, 3);
  EXPECT_EQ(s.cutting.method, CutMethod::kSnap);
  EXPECT_DOUBLE_EQ(s.cutting.tolerance, 0.05);
  EXPECT_EQ(s.cutting.strokes, StrokeSurfaceKind::kPlane);
  EXPECT_EQ(s.headless.steps, 250);
}

TEST_F(SceneTest, PathsResolveAgainstTheSceneFolder) {
  fs::create_directories(m_dir / "config" / "paths");
  fs::create_directories(m_dir / "assets");
  write("assets/a.msh", "x");
  write("config/paths/s.csv", kCsvHeader + "0,s,0,0,0,1,0,0,0,0\n");
  const std::string toml =
      "[[organ]]\nname = \"a\"\nmesh = \"../assets/a.msh\"\n"
      "[[tool]]\nname = \"s\"\nkind = \"scissors\"\ndevice = \"script:paths/s.csv\"\n"
      "[record]\npath = \"../out/r.lapr\"\n";
  write("config/scene.toml", toml);
  const Scene s = load_scene(m_dir / "config" / "scene.toml");
  EXPECT_EQ(s.organs[0].mesh, m_dir / "assets" / "a.msh");
  EXPECT_EQ(s.tools[0].device.script, m_dir / "config" / "paths" / "s.csv");
  EXPECT_EQ(s.record.path, m_dir / "out" / "r.lapr");

  // Absolute paths stay absolute.
  const Scene abs =
      parse("[[organ]]\nname = \"a\"\nmesh = \"" + (m_dir / "assets" / "a.msh").string() + "\"\n");
  EXPECT_EQ(abs.organs[0].mesh, m_dir / "assets" / "a.msh");
}

TEST_F(SceneTest, RelativeScenePathResolvesFromTheWorkingDirectory) {
  const fs::path old = fs::current_path();
  fs::current_path(m_dir);
  const Scene s = parse_scene_text(kOrgan, "scene.toml");
  fs::current_path(old);
  EXPECT_EQ(s.organs[0].mesh, m_dir / "organ.msh");
  EXPECT_EQ(s.file, fs::path("scene.toml"));
}

TEST_F(SceneTest, QualityPresetSetsDefaultsAndExplicitKeysWin) {
  // What each preset picks is tested against the measured curves in test_presets.cpp; here the
  // loader's part: the preset applies, and explicit keys win over it.
  const Scene fast = parse("[scene]\nquality = \"fast\"\n" + kOrgan);
  EXPECT_EQ(fast.settings.quality, Quality::kFast);
  ASSERT_TRUE(fast.settings.accuracy_target.has_value());
  EXPECT_DOUBLE_EQ(*fast.settings.accuracy_target, quality_accuracy_target(Quality::kFast));
  const PresetChoice c = choose_preset(*fast.settings.accuracy_target, Quality::kFast);
  EXPECT_EQ(fast.solver.max_iterations, c.solver->max_iterations);
  EXPECT_EQ(fast.render.tessellation, c.tessellation->level);
  const Scene accurate = parse("[scene]\nquality = \"accurate\"\n" + kOrgan +
                               "[render]\ntessellation = 5\n[solver]\nmax_iterations = 7\n");
  EXPECT_EQ(accurate.render.tessellation, 5);
  EXPECT_EQ(accurate.solver.max_iterations, 7);
  const Scene none = parse(kOrgan);
  EXPECT_FALSE(none.settings.accuracy_target.has_value());
  EXPECT_EQ(none.solver.max_iterations, scene_default_solver().max_iterations);
}

TEST_F(SceneTest, AccuracyTargetOverridesTheQualityTarget) {
  const Scene s = parse("[scene]\nquality = \"fast\"\naccuracy_target = 0.001\n" + kOrgan);
  ASSERT_TRUE(s.settings.accuracy_target.has_value());
  EXPECT_DOUBLE_EQ(*s.settings.accuracy_target, 0.001);
  const PresetChoice c = choose_preset(0.001, Quality::kFast);
  EXPECT_LE(c.solver->rel_error, 0.001);
  EXPECT_EQ(s.solver.max_iterations, c.solver->max_iterations);
  EXPECT_EQ(s.solver.kind, c.solver->kind);
  expect_error("[scene]\naccuracy_target = 0\n" + kOrgan, 2, "scene.accuracy_target",
               "relative displacement error");
  expect_error("[scene]\naccuracy_target = 1.5\n" + kOrgan, 2, "scene.accuracy_target",
               "relative displacement error");
}

TEST_F(SceneTest, EffectsAreASet) {
  const Scene s = parse("[scene]\neffects = [\"surface\", \"render\", \"fem\"]\n" + kOrgan);
  EXPECT_TRUE(s.settings.has(Effect::kRender));
  EXPECT_FALSE(s.settings.has(Effect::kGravity));
  EXPECT_EQ(*s.settings.effects.begin(), Effect::kFem);  // enum order, not listing order
  const Scene none = parse("[scene]\neffects = []\n" + kOrgan);
  EXPECT_TRUE(none.settings.effects.empty());
}

TEST_F(SceneTest, HapticsWithADeviceToolLoads) {
  const Scene s = parse("[scene]\neffects = [\"haptics\"]\n" + kOrgan +
                        "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"rig-emulated\"\n");
  EXPECT_TRUE(s.settings.has(Effect::kHaptics));
  EXPECT_EQ(s.tools[0].device.kind, DeviceKind::kRigEmulated);
}

// ---------------------------------------------------------------------------------------------
// Errors: one test per kind

TEST_F(SceneTest, MissingSceneFile) {
  try {
    (void)load_scene(m_dir / "nope.toml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_NE(std::string(e.what()).find("nope.toml"), std::string::npos);
  }
}

// A directory opens as a stream that reads nothing: it was parsed as an empty scene and reported
// as "the scene has no organ", sending the user to look inside a file that is not there.
TEST_F(SceneTest, SceneFileThatIsADirectory) {
  fs::create_directories(m_dir / "dir.toml");
  try {
    (void)load_scene(m_dir / "dir.toml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.file(), (m_dir / "dir.toml").string());
    EXPECT_NE(e.message().find("is a directory"), std::string::npos) << e.what();
  }
}

TEST_F(SceneTest, TomlSyntaxErrorGivesItsLine) {
  try {
    (void)parse(kOrgan + "young = = 3\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 4) << e.what();
    EXPECT_NE(std::string(e.what()).find("TOML syntax error"), std::string::npos) << e.what();
  }
}

TEST_F(SceneTest, UnknownTopLevelKeyListsTheAllowedOnes) {
  expect_error(kOrgan + "[solvr]\nkind = \"pcg\"\n", 4, "solvr",
               "one of: scene, organ, support, solver");
}

TEST_F(SceneTest, UnknownKeyInATable) {
  expect_error("[scene]\ndt = 0.01\ntimestep = 0.01\n" + kOrgan, 3, "scene.timestep",
               "one of: dt, gravity, effects, quality, accuracy_target");
  expect_error(kOrgan + "yong = 3000\n", 4, "organ[0].yong", "one of: name, mesh, groups, young");
  expect_error(kOrgan + "damping = { mass = 0.1, stiff = 0.2 }\n", 4, "organ[0].damping.stiff",
               "one of: mass, stiffness");
  expect_error(
      kOrgan + "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"mouse\"\nport = 1\n", 8,
      "tool[0].port", "one of: name, kind, device, hand, trocar");
  expect_error(kOrgan + "[render]\nmsaa = 4\n", 5, "render.msaa", "tessellation");
  expect_error(kOrgan + "[headless]\nframes = 4\n", 5, "headless.frames", "one of: steps");
}

TEST_F(SceneTest, WrongType) {
  expect_error(kOrgan + "young = \"soft\"\n", 4, "organ[0].young",
               "expected a number, got a string");
  expect_error(kOrgan + "[render]\ntessellation = 2.5\n", 5, "render.tessellation",
               "expected an integer, got a float");
  expect_error("[scene]\neffects = \"fem\"\n" + kOrgan, 2, "scene.effects", "expected an array");
  expect_error("[scene]\neffects = [\"fem\", \"bleeding\"]\n" + kOrgan, 2, "scene.effects",
               "no artery is named");
  expect_error("[scene]\neffects = [\"fem\", \"smoke\"]\n" + kOrgan, 2, "scene.effects",
               "\"smoke\" needs effect \"cautery\"");
  expect_error(kOrgan + "[render]\nlooks = { 1 = \"plastic\" }\n", 5, "render.looks.1",
               "unknown tissue \"plastic\"");
  expect_error(kOrgan + "[render]\nlooks = { omentum = \"fat\" }\n", 5, "render.looks.omentum",
               "unknown group \"omentum\"");
  expect_error("[scene]\ngravity = [0, \"down\", 0]\n" + kOrgan, 2, "scene.gravity[1]",
               "expected a number");
  expect_error("scene = 3\n" + kOrgan, 1, "scene", "expected a table");
  expect_error(kOrgan + "name2 = 1\n", 4, "organ[0].name2");
  expect_error("[[organ]]\nname = 7\nmesh = \"organ.msh\"\n", 2, "organ[0].name",
               "expected a string");
}

TEST_F(SceneTest, NonPositiveYoung) {
  expect_error(kOrgan + "young = -5\n", 4, "organ[0].young", "must be > 0, got -5");
  expect_error(kOrgan + "young = 0.0\n", 4, "organ[0].young", "must be > 0");
}

TEST_F(SceneTest, NonFiniteNumber) {
  expect_error(kOrgan + "young = inf\n", 4, "organ[0].young", "finite");
  expect_error(kOrgan + "density = nan\n", 4, "organ[0].density", "finite");
}

TEST_F(SceneTest, PoissonOutOfRange) {
  expect_error(kOrgan + "poisson = 0.5\n", 4, "organ[0].poisson", "must be < 0.5");
  expect_error(kOrgan + "poisson = 0.7\n", 4, "organ[0].poisson", "must be < 0.5");
  expect_error(kOrgan + "poisson = -1.0\n", 4, "organ[0].poisson", "must be > -1");
}

TEST_F(SceneTest, NonPositiveDensity) {
  expect_error(kOrgan + "density = 0\n", 4, "organ[0].density", "must be > 0");
}

TEST_F(SceneTest, NegativeDamping) {
  expect_error(kOrgan + "damping = { mass = -0.1 }\n", 4, "organ[0].damping.mass", ">= 0");
  expect_error(kOrgan + "plasticity = { creep = -1 }\n", 4, "organ[0].plasticity.creep", ">= 0");
}

TEST_F(SceneTest, BadTimeStep) {
  expect_error("[scene]\ndt = 0\n" + kOrgan, 2, "scene.dt", "must be > 0");
  expect_error("[scene]\ndt = -0.01\n" + kOrgan, 2, "scene.dt", "must be > 0");
  expect_error("[scene]\ndt = 5\n" + kOrgan, 2, "scene.dt", "must be <= 1");
}

TEST_F(SceneTest, BadVectorLength) {
  expect_error("[scene]\ngravity = [0, -9.81]\n" + kOrgan, 2, "scene.gravity", "3 numbers");
}

TEST_F(SceneTest, NoOrgan) {
  expect_error("[scene]\ndt = 0.01\n", 0, "organ", "no organ");
  expect_error("organ = []\n", 1, "organ", "no organ");
  expect_error("organ = \"liver\"\n", 1, "organ", "array of tables");
}

TEST_F(SceneTest, MissingRequiredKey) {
  expect_error("[scene]\ndt = 0.01\n[[organ]]\nname = \"a\"\n", 3, "organ[0].mesh",
               "missing required key");
  expect_error("[[organ]]\nmesh = \"organ.msh\"\n", 1, "organ[0].name", "missing required key");
  expect_error(kOrgan + "[[tool]]\nname = \"g\"\nkind = \"grasper\"\n", 4, "tool[0].device",
               "missing required key");
}

TEST_F(SceneTest, MissingMeshFile) {
  expect_error("[[organ]]\nname = \"a\"\nmesh = \"../nowhere/liver.msh\"\n", 3, "organ[0].mesh",
               "not found");
  expect_error("[[organ]]\nname = \"a\"\nmesh = \"paths\"\n", 3, "organ[0].mesh",
               "not found");  // a folder is not a mesh file
}

TEST_F(SceneTest, DuplicateOrganName) {
  expect_error(kOrgan + kOrgan, 5, "organ[1].name", "duplicate organ name");
}

TEST_F(SceneTest, BadGroups) {
  expect_error(kOrgan + "groups = { one = \"appendix\" }\n", 4, "organ[0].groups.one",
               "not a group id");
  expect_error(kOrgan + "groups = { 1 = \"a\", 2 = \"a\" }\n", 4, "organ[0].groups.2",
               "used twice");
  expect_error(kOrgan + "groups = { 1 = 5 }\n", 4, "organ[0].groups.1", "expected a string");
  expect_error(kOrgan + "groups = { 1 = \"a\" }\n" +
                   "[[organ]]\nname = \"b\"\nmesh = \"colon.msh\"\ngroups = { 1 = \"b\" }\n",
               8, "organ[1].groups.1", "already belongs to organ[0]");
}

TEST_F(SceneTest, BadGroupMaterial) {
  expect_error(kOrgan + "groups = { 1 = \"a\" }\n[organ.material.cecum]\nyoung = 1\n", 5,
               "organ[0].material.cecum", "unknown group \"cecum\"");
  expect_error(kOrgan + "[organ.material.1]\nyoung = -1\n", 5, "organ[0].material.1.young",
               "must be > 0");
  expect_error(kOrgan + "[organ.material.1]\nfixed = 1\n", 5, "organ[0].material.1.fixed",
               "one of: young, poisson");
  expect_error(kOrgan + "material = { 1 = 3 }\n", 4, "organ[0].material.1", "expected a table");
}

TEST_F(SceneTest, BadFixed) {
  expect_error(kOrgan + "fixed = { box = [[0, 0, 0], [1, -1, 1]] }\n", 4, "organ[0].fixed.box",
               "min corner exceeds max");
  expect_error(kOrgan + "fixed = { box = [[0, 0, 0]] }\n", 4, "organ[0].fixed.box", "2 corners");
  expect_error(kOrgan + "fixed = { groups = [\"cecum\"] }\n", 4, "organ[0].fixed.groups[0]",
               "unknown group");
  expect_error(kOrgan + "fixed = { nodes = [1, -2] }\n", 4, "organ[0].fixed.nodes[1]",
               "[0, 2147483647]");
  expect_error(kOrgan + "fixed = { plane = 1 }\n", 4, "organ[0].fixed.plane",
               "one of: box, groups, nodes");
}

TEST_F(SceneTest, BadTransform) {
  expect_error(kOrgan + "transform = { scale = 0 }\n", 4, "organ[0].transform.scale", "> 0");
  expect_error(kOrgan + "transform = { rotate = [0, 0, 90] }\n", 4, "organ[0].transform.rotate",
               "rotate_deg");
}

TEST_F(SceneTest, BadSolver) {
  expect_error(kOrgan + "[solver]\nkind = \"lu\"\n", 5, "solver.kind",
               "one of: pcg, cholmod, pcg-cholmod");
  expect_error(kOrgan + "[solver]\ntolerance = 0\n", 5, "solver.tolerance", "> 0");
  expect_error(kOrgan + "[solver]\nmax_iterations = 0\n", 5, "solver.max_iterations",
               "[1, 1000000]");
  expect_error(kOrgan + "[solver]\nafter_cut = \"later\"\n", 5, "solver.after_cut",
               "\"patch\" or \"factor\"");
  expect_error(kOrgan + "[solver]\npatch_rings = 9\n", 5, "solver.patch_rings", "[0, 8]");
}

TEST_F(SceneTest, BadRender) {
  expect_error(kOrgan + "[render]\ntessellation = 0\n", 5, "render.tessellation", "[1, 16]");
  expect_error(kOrgan + "[render]\ntessellation = 17\n", 5, "render.tessellation", "[1, 16]");
  expect_error(kOrgan + "[render]\nshape_factor = 1.5\n", 5, "render.shape_factor", "<= 1");
  expect_error(kOrgan + "[render]\nwidth = 0\n", 5, "render.width", "[1, 16384]");
}

TEST_F(SceneTest, BadRecordCuttingHeadlessQuality) {
  expect_error(kOrgan + "[record]\nhash_every = 0\n", 5, "record.hash_every", ">= 1");
  expect_error(kOrgan + "[record]\nsnapshot_every_s = -1\n", 5, "record.snapshot_every_s", ">= 0");
  expect_error(kOrgan + "[record]\npath = \"\"\n", 5, "record.path", "empty path");
  expect_error(kOrgan + "[cutting]\nmethod = \"laser\"\n", 5, "cutting.method",
               "pattern, remove, snap");
  expect_error(kOrgan + "[cutting]\ntolerance = 0.5\n", 5, "cutting.tolerance", "< 0.5");
  expect_error(kOrgan + "[cutting]\nstrokes = \"curved\"\n", 5, "cutting.strokes", "swept, plane");
  expect_error(kOrgan + "[headless]\nsteps = 0\n", 5, "headless.steps", ">= 1");
  expect_error("[scene]\nquality = \"ultra\"\n" + kOrgan, 2, "scene.quality",
               "fast, balanced, accurate");
}

TEST_F(SceneTest, UnknownEffect) {
  expect_error("[scene]\neffects = [\"fem\",\n  \"fluids\"]\n" + kOrgan, 3, "scene.effects[1]",
               "unknown value \"fluids\"");
}

TEST_F(SceneTest, DuplicateEffect) {
  expect_error("[scene]\neffects = [\"fem\", \"fem\"]\n" + kOrgan, 2, "scene.effects[1]",
               "listed twice");
}

TEST_F(SceneTest, EffectDependencies) {
  expect_error("[scene]\neffects = [\"gravity\"]\n" + kOrgan, 2, "scene.effects",
               "\"gravity\" needs effect \"fem\"");
  expect_error("[scene]\neffects = [\"plasticity\"]\n" + kOrgan, 2, "scene.effects",
               "\"plasticity\" needs effect \"fem\"");
  expect_error("[scene]\neffects = [\"fem\", \"contact\"]\n" + kOrgan, 2, "scene.effects",
               "\"contact\" needs effect \"surface\"");
  expect_error("[scene]\neffects = [\"surface\", \"contact\"]\n" + kOrgan, 2, "scene.effects",
               "\"contact\" needs effect \"fem\"");
  expect_error("[scene]\neffects = [\"render\"]\n" + kOrgan, 2, "scene.effects",
               "\"render\" needs effect \"surface\"");
  expect_error("[scene]\neffects = [\"fem\", \"surface\", \"clips\"]\n" + kOrgan, 2,
               "scene.effects", "\"clips\" needs effect \"contact\"");
}

TEST_F(SceneTest, AClipApplierNeedsTheClipsEffect) {
  const std::string applier =
      "[[tool]]\nname = \"clipper\"\nkind = \"clip-applier\"\ndevice = \"mouse\"\n";
  expect_error("[scene]\neffects = [\"fem\", \"surface\", \"contact\"]\n" + kOrgan + applier, 8,
               "tool[0].kind", "effect \"clips\" is not listed");
  const Scene s = parse("[scene]\neffects = [\"fem\", \"surface\", \"contact\", \"clips\"]\n" +
                        kOrgan + applier);
  ASSERT_EQ(s.tools.size(), 1u);
  EXPECT_EQ(s.tools[0].kind, ToolKind::kClipApplier);
  EXPECT_TRUE(s.settings.has(Effect::kClips));
  expect_error(kOrgan + "[[tool]]\nname = \"c\"\nkind = \"clipper\"\ndevice = \"mouse\"\n", 6,
               "tool[0].kind", "clip-applier");
}

TEST_F(SceneTest, OnlyAHooksScriptMayPressTheCauteryPedal) {
  write("paths/pedal.csv", kCsvHeader.substr(0, kCsvHeader.size() - 1) + ",buttons\n" +
                               "0,hook,0,0,0,1,0,0,0,0,0\n"
                               "1,hook,0,0,0,1,0,0,0,0,2\n"
                               "0,scissors,0,0,0,1,0,0,0,0,1\n"
                               "1,scissors,0,0,0,1,0,0,0,0,2\n");
  const std::string head = "[scene]\neffects = [\"fem\", \"cautery\", \"cutting\"]\n" + kOrgan;
  const Scene s = parse(
      head + "[[tool]]\nname = \"hook\"\nkind = \"hook\"\ndevice = \"script:paths/pedal.csv\"\n");
  EXPECT_EQ(s.tools[0].kind, ToolKind::kHook);
  expect_error(head +
                   "[[tool]]\nname = \"scissors\"\nkind = \"scissors\"\n"
                   "device = \"script:paths/pedal.csv\"\n",
               9, "tool[0].device",
               "presses the cautery pedal (buttons bit 1) for tool \"scissors\"");
}

TEST_F(SceneTest, AHookNeedsTheCauteryEffect) {
  const std::string hook = "[[tool]]\nname = \"hook\"\nkind = \"hook\"\ndevice = \"mouse\"\n";
  expect_error("[scene]\neffects = [\"fem\", \"cutting\"]\n" + kOrgan + hook, 8, "tool[0].kind",
               "effect \"cautery\" is not listed");
  const Scene s = parse("[scene]\neffects = [\"fem\", \"cautery\"]\n" + kOrgan + hook);
  ASSERT_EQ(s.tools.size(), 1u);
  EXPECT_EQ(s.tools[0].kind, ToolKind::kHook);
}

TEST_F(SceneTest, HapticsNeedsADeviceTool) {
  expect_error("[scene]\neffects = [\"haptics\"]\n" + kOrgan, 2, "scene.effects", "haptics");
  expect_error("[scene]\neffects = [\"haptics\"]\n" + kOrgan +
                   "[[tool]]\nname = \"grasper\"\nkind = \"endoscope\"\n"
                   "device = \"script:paths/p.csv\"\n",
               2, "scene.effects", "needs a tool driven by a device");
}

TEST_F(SceneTest, DuplicateToolName) {
  const std::string tool = "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"mouse\"\n";
  expect_error(kOrgan + tool + tool, 9, "tool[1].name", "duplicate tool name \"g\"");
}

TEST_F(SceneTest, BadToolKindDeviceHandTrocar) {
  const std::string head = kOrgan + "[[tool]]\nname = \"g\"\n";
  expect_error(head + "kind = \"morcellator\"\ndevice = \"mouse\"\n", 6, "tool[0].kind",
               "scissors, grasper, endoscope");
  expect_error(head + "kind = \"grasper\"\ndevice = \"joystick\"\n", 7, "tool[0].device",
               "unknown device");
  expect_error(head + "kind = \"grasper\"\ndevice = \"script\"\n", 7, "tool[0].device",
               "script:FILE");
  expect_error(head + "kind = \"grasper\"\ndevice = \"mouse\"\nhand = \"both\"\n", 8,
               "tool[0].hand", "left, right");
  expect_error(head + "kind = \"grasper\"\ndevice = \"mouse\"\ntrocar = [0, 0]\n", 8,
               "tool[0].trocar", "3 numbers");
  expect_error(kOrgan + "[[tool]]\nname = \"a b\"\nkind = \"grasper\"\ndevice = \"mouse\"\n", 5,
               "tool[0].name", "bad tool name");
  expect_error(kOrgan + "tool = 1\n", 4, "organ[0].tool");  // inside [[organ]]: a typo there
  expect_error("tool = 1\n" + kOrgan, 1, "tool", "array of tables");
}

TEST_F(SceneTest, MissingScriptFile) {
  expect_error(
      kOrgan + "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"script:nope.csv\"\n", 7,
      "tool[0].device", "script file \"nope.csv\" not found");
  expect_error(kOrgan + "[[tool]]\nname = \"g\"\nkind = \"grasper\"\ndevice = \"script:\"\n", 7,
               "tool[0].device", "empty path");
}

TEST_F(SceneTest, ScriptWithoutRowsForTheTool) {
  expect_error(kOrgan + "[[tool]]\nname = \"camera\"\nkind = \"endoscope\"\n" +
                   "device = \"script:paths/p.csv\"\n",
               7, "tool[0].device", "no rows for tool \"camera\"");
}

TEST_F(SceneTest, BadScriptReportsTheCsvLine) {
  write("paths/bad.csv", kCsvHeader + "0,g,0,0,0,1,0,0,0,0\n0,g,0,0,0,1,0,0\n");
  try {
    (void)parse(kOrgan + "[[tool]]\nname = \"g\"\nkind = \"grasper\"\n" +
                "device = \"script:paths/bad.csv\"\n");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (m_dir / "paths" / "bad.csv").string());
    EXPECT_EQ(e.line(), 3);
  }
}

// ---------------------------------------------------------------------------------------------
// Bundled scenes

void expect_bundled_scene_loads(const std::string& scene, const std::string& asset) {
  const fs::path root = ::serosa::test_paths::source_dir();
  if (!fs::exists(root / asset)) {
    GTEST_SKIP() << asset << " has not been generated yet (tools/ writes it); " << scene
                 << " cannot be checked without it";
  }
  const Scene s = load_scene(root / scene);
  EXPECT_FALSE(s.organs.empty());
  EXPECT_EQ(s.organs[0].mesh, (root / asset).lexically_normal());
}

TEST(BundledScenes, AppendectomyLoads) {
  expect_bundled_scene_loads("config/transection.toml", "assets/appendectomy_coarse.msh");
  if (IsSkipped()) return;
  const Scene s =
      load_scene(fs::path(::serosa::test_paths::source_dir()) / "config/transection.toml");
  // No "gravity": the scene does not simulate what holds the organs up (see its header).
  EXPECT_FALSE(s.settings.has(Effect::kGravity));
  for (const Effect e : {Effect::kFem, Effect::kCutting, Effect::kSurface, Effect::kContact,
                         Effect::kRender, Effect::kRecord}) {
    EXPECT_TRUE(s.settings.has(e)) << effect_name(e);
  }
  ASSERT_TRUE(s.tool_index("grasper") && s.tool_index("scissors") && s.tool_index("endoscope"));
  EXPECT_EQ(s.tools[*s.tool_index("scissors")].kind, ToolKind::kScissors);
  EXPECT_EQ(s.organs[0].group_id("mesoappendix"), 2);
  EXPECT_FALSE(s.organs[0].fixed.empty());
}

TEST(BundledScenes, BeamLoads) {
  expect_bundled_scene_loads("config/beam.toml", "assets/beam_coarse.msh");
  if (IsSkipped()) return;
  const Scene s = load_scene(fs::path(::serosa::test_paths::source_dir()) / "config/beam.toml");
  EXPECT_EQ(s.settings.effects, (std::set<Effect>{Effect::kFem, Effect::kGravity}));
  ASSERT_TRUE(s.organs[0].fixed.box.has_value());
}

}  // namespace
}  // namespace serosa
