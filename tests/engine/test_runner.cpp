#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "engine/runner.h"
#include "engine/sim_state.h"

namespace serosa {
namespace {

// Records the order in which stages ran and the context each saw.
class Probe final : public Stage {
 public:
  Probe(std::string name, std::vector<std::string>& log) : m_name(std::move(name)), m_log(log) {}
  std::string_view name() const noexcept override { return m_name; }
  void step(const StepContext& ctx, SimState&) override {
    m_log.push_back(m_name + "@" + std::to_string(ctx.step));
  }

 private:
  std::string m_name;
  std::vector<std::string>& m_log;
};

TEST(Runner, CallsStagesInOrderAndAdvancesTime) {
  std::vector<std::string> log;
  Runner r(0.005);
  // Added out of order: the step runs them in the order of their places.
  r.add(Slot::surface, std::make_unique<Probe>("surface", log));
  r.add(Slot::fem, std::make_unique<Probe>("fem", log));
  SimState s;
  r.run(s, 3);
  EXPECT_EQ(log, (std::vector<std::string>{"fem@0", "surface@0", "fem@1", "surface@1", "fem@2",
                                           "surface@2"}));
  EXPECT_EQ(s.step, 3u);
  EXPECT_DOUBLE_EQ(s.time_s, 0.015);
  ASSERT_EQ(r.timings().size(), 2u);
  EXPECT_EQ(r.timings()[0].name, "fem");
  EXPECT_EQ(r.timings()[0].calls, 3u);
}

TEST(Runner, RejectsBadDt) { EXPECT_THROW(Runner(0.0), std::invalid_argument); }

TEST(StateHash, EqualStatesHashEqualAndAnyChangeShows) {
  SimState a;
  a.mesh.add_node(Vec3(0, 0, 0));
  a.mesh.add_node(Vec3(1, 0, 0));
  SimState b = a;
  EXPECT_EQ(state_hash(a), state_hash(b));
  b.mesh.x[1].y() = 1e-12;
  EXPECT_NE(state_hash(a), state_hash(b));
  b = a;
  b.time_s = 1.0;
  EXPECT_NE(state_hash(a), state_hash(b));
}

}  // namespace
}  // namespace serosa
