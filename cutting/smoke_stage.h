// The "smoke" stage (after cutting, effect "smoke"): surgical smoke. Each node a live hook
// coagulates this step (SimState::blocks.cutting.coagulated; not the nodes a cut adds, which take
// their parents' marks) raises a puff there, at most kPuffsPerStep a step; a puff rises against
// gravity at kRiseMps, drifts sideways, swells from kStartRadiusM by kGrowMps and thins out over
// kLifeS, then clears. At most kMaxPuffs live at once (the oldest gives way), held in storage sized
// once, so a step allocates nothing. Its ring is SimState::blocks.smoke. It publishes
// SimState::shared.smoke for the view.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"
#include "engine/state_blocks.h"

namespace serosa::cutting {

class SmokeStage final : public Stage {
 public:
  static constexpr std::size_t kMaxPuffs = 96;
  static constexpr int kPuffsPerStep = 3;
  static constexpr double kLifeS = 2.5;           ///< a puff clears after this long, s
  static constexpr double kRiseMps = 0.015;       ///< m/s against gravity
  static constexpr double kDriftMps = 0.006;      ///< m/s sideways at most
  static constexpr double kStartRadiusM = 0.003;  ///< m
  static constexpr double kGrowMps = 0.008;       ///< m/s
  static constexpr double kStartDensity = 0.6;    ///< [0, 1]

  explicit SmokeStage(const Scene& scene);
  [[nodiscard]] std::string_view name() const noexcept override { return "smoke"; }
  void step(const StepContext& ctx, SimState& state) override;
  void adopt(SimState& state) override;

 private:
  using Puff = SmokeBlock::Puff;
  static void emit(SmokeBlock& b, const Vec3& at, double t);
  static void publish(double t, SimState& state);

  Vec3 m_up;              // unit, against gravity
  Vec3 m_side1, m_side2;  // unit, across it
};

}  // namespace serosa::cutting
