// An effect the scene does not list costs nothing (docs/ARCHITECTURE.md "Effects"): no stage, no
// timer, no allocation in a step. This test executable replaces the global operator new with a
// counting one, so it can compare the composed pipeline of a fem-only scene, step by step, with
// a pipeline built by hand from exactly the stages that scene needs (tools, FEM, metrics) — while
// the scripted scissors and grasper close on the tissue, which would cut, grasp and touch if
// "cutting", "surface" or "contact" were listed. The same scene with "cutting" listed shows the
// counter sees what an effect allocates.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <new>

#include "app/assemble_state.h"
#include "app/compose.h"
#include "app_test_util.h"
#include "engine/runner.h"
#include "engine/scene/scene.h"
#include "engine/script_tool_stage.h"
#include "engine/sim_state.h"
#include "fem/fem_stage.h"
#include "metrics/metrics_stage.h"

namespace {

std::atomic<std::uint64_t> g_allocs{0};  // NOLINT: the counting allocator's state
std::atomic<std::uint64_t> g_bytes{0};   // NOLINT

void* counted(std::size_t n) {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  g_bytes.fetch_add(n, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}

void* counted_nothrow(std::size_t n) noexcept {
  g_allocs.fetch_add(1, std::memory_order_relaxed);
  g_bytes.fetch_add(n, std::memory_order_relaxed);
  return std::malloc(n == 0 ? 1 : n);
}

}  // namespace

// Replaced for the whole test executable (counting only; memory comes from malloc). Every
// unaligned form is replaced, nothrow ones included (the standard library's temporary buffers
// use them): a form left to the runtime would hand out memory our delete frees with free().
void* operator new(std::size_t n) { return counted(n); }
void* operator new[](std::size_t n) { return counted(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return counted_nothrow(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return counted_nothrow(n); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace serosa::app {
namespace {

using namespace serosa::app::testing;

struct Count {
  std::uint64_t allocs = 0;
  std::uint64_t bytes = 0;
  bool operator==(const Count&) const = default;
};

template <class F>
Count count_during(F&& f) {
  const std::uint64_t a0 = g_allocs.load(), b0 = g_bytes.load();
  f();
  return {g_allocs.load() - a0, g_bytes.load() - b0};
}

// The beam (fixed at x = 0), scissors (shaft +y, blade plane x = 5.25 cm) closing across it and a
// grasper closing on its free end, both from step 0; effects as given.
Scene beam_scene(const fs::path& dir, const std::string& effects) {
  std::ofstream(dir / "path.csv")
      << "t,tool,px,py,pz,qw,qx,qy,qz,jaw\n"
         "0.00,scissors,0.0525,0.008,0,0.5,-0.5,-0.5,-0.5,1.2\n"
         "0.10,scissors,0.0525,0.008,0,0.5,-0.5,-0.5,-0.5,0\n"
         "0.00,grasper,0.095,0.002,0,0.7071067811865476,0.7071067811865476,0,0,0.9\n"
         "0.10,grasper,0.095,0.002,0,0.7071067811865476,0.7071067811865476,0,0,0\n";
  std::string toml =
      "[scene]\ndt = 0.005\neffects = [" + effects + "]\n[[organ]]\nname = \"beam\"\n";
  toml.append("mesh = \"").append(source("assets/beam_coarse.msh").string()).append("\"\n");
  toml.append("young = 2e4\npoisson = 0.3\ndensity = 1000\n");
  toml.append("fixed = { box = [[-0.001, -1, -1], [0.0001, 1, 1]] }\n[solver]\nkind = \"pcg\"\n");
  toml.append("[[tool]]\nname = \"scissors\"\nkind = \"scissors\"\ndevice = \"script:path.csv\"\n");
  toml.append("[[tool]]\nname = \"grasper\"\nkind = \"grasper\"\ndevice = \"script:path.csv\"\n");
  std::ofstream(dir / "scene.toml") << toml;
  return load_scene(dir / "scene.toml");
}

TEST(EffectsCost, UnlistedEffectsAllocateNothingAndTakeNoTimeInAStep) {
  const fs::path dir = out_dir("effects_cost");
  const Scene scene = beam_scene(dir, "\"fem\"");

  // Composed: only what "fem" needs.
  AssembledScene composed_state = assemble_state(scene);
  Composition comp = compose(scene, composed_state);
  EXPECT_EQ(comp.cutting, nullptr);
  EXPECT_EQ(comp.surface, nullptr);
  EXPECT_EQ(comp.contact, nullptr);
  std::vector<std::string> names;
  for (const StageTiming& t : comp.runner->timings()) names.push_back(t.name);
  EXPECT_EQ(names, (std::vector<std::string>{"tools", "fem", "metrics"}));

  // By hand: the same three stages, nothing else.
  AssembledScene hand_state = assemble_state(scene);
  Runner hand(scene.settings.dt_s);
  hand.add(Slot::tools, std::make_unique<ScriptToolStage>(scene));
  hand.add(Slot::fem, std::make_unique<fem::FemStage>(fem_config(scene, hand_state)));
  hand.add(Slot::metrics, std::make_unique<MetricsStage>(scene, lame_table(scene, hand_state)));

  // Step by step (the jaws close over steps 0..19), the composed pipeline allocates exactly
  // what the hand-built one does, and reaches the same state.
  for (int step = 0; step < 24; ++step) {
    const Count c = count_during([&] { comp.runner->step(composed_state.state); });
    const Count h = count_during([&] { hand.step(hand_state.state); });
    EXPECT_EQ(c.allocs, h.allocs) << "step " << step;
    EXPECT_EQ(c.bytes, h.bytes) << "step " << step;
  }
  EXPECT_EQ(state_hash(composed_state.state), state_hash(hand_state.state));
  EXPECT_EQ(composed_state.state.mesh.num_tets(), 480);  // nothing cut

  // The counter does see an effect's cost: listing "cutting" allocates more over the same steps.
  const fs::path dir2 = out_dir("effects_cost_cutting");
  const Scene cutting_scene = beam_scene(dir2, "\"fem\", \"cutting\"");
  AssembledScene cut_state = assemble_state(cutting_scene);
  Composition cut_comp = compose(cutting_scene, cut_state);
  const Count with_cutting = count_during([&] { cut_comp.runner->run(cut_state.state, 24); });
  AssembledScene again = assemble_state(scene);
  Composition plain = compose(scene, again);
  const Count without = count_during([&] { plain.runner->run(again.state, 24); });
  EXPECT_GT(with_cutting.bytes, without.bytes);
  EXPECT_GT(cut_state.state.mesh.num_tets(), 480);  // it did cut
  ASSERT_NE(cut_comp.cutting, nullptr);
}

}  // namespace
}  // namespace serosa::app
