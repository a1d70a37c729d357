// serosa headless end to end: the bundled scenes run, the report is honest, outputs round trip.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/headless.h"
#include "engine/input_error.h"
#include "engine/mesh_io.h"
#include "engine/sim_state.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;

fs::path out_dir(const std::string& name) {
  const fs::path d = fs::path(SEROSA_BINARY_DIR) / "test-output" / "app" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(Headless, BeamSceneRunsAndReportsWhatItSimulated) {
  const fs::path dir = out_dir("beam");
  HeadlessOptions o;
  o.scene = fs::path(SEROSA_SOURCE_DIR) / "config" / "beam.toml";
  o.steps = 20;
  o.report = dir / "report.json";
  o.export_final = dir / "final.msh";
  o.progress = false;
  const auto report = run_headless(o);
  EXPECT_EQ(report["steps"], 20);
  EXPECT_TRUE(fs::exists(dir / "report.json"));
  EXPECT_EQ(report["effects"]["simulated"][0], "fem");
  EXPECT_EQ(report["fem"]["rejected"], 0);
  // The exported mesh is the final state: same topology, deformed positions.
  const TetMesh final_mesh = read_mesh(dir / "final.msh");
  EXPECT_EQ(final_mesh.num_tets(), report["mesh_final"]["tets"].get<int>());
  EXPECT_TRUE(report["mesh_final"]["valid"].get<bool>());
}

TEST(Headless, SameInputsGiveTheSameStateHash) {
  HeadlessOptions o;
  o.scene = fs::path(SEROSA_SOURCE_DIR) / "config" / "beam.toml";
  o.steps = 10;
  o.progress = false;
  EXPECT_EQ(run_headless(o)["state_hash"], run_headless(o)["state_hash"]);
}

TEST(Headless, AppendectomyWritesPictures) {
  const fs::path dir = out_dir("appendectomy");
  HeadlessOptions o;
  o.scene = fs::path(SEROSA_SOURCE_DIR) / "config" / "appendectomy.toml";
  o.steps = 4;
  o.frames = dir / "frames";
  o.frame_count = 2;
  o.progress = false;
  const auto report = run_headless(o);
  ASSERT_EQ(report["frames"].size(), 2u);
  for (const auto& f : report["frames"]) EXPECT_GT(fs::file_size(f.get<std::string>()), 1000u);
}

TEST(Headless, BadSceneIsAnInputErrorNamingTheFile) {
  const fs::path dir = out_dir("bad");
  std::ofstream(dir / "bad.toml") << "[scene]\ndt = -1\n";
  HeadlessOptions o;
  o.scene = dir / "bad.toml";
  o.progress = false;
  try {
    (void)run_headless(o);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace serosa::app
