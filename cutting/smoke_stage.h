// The "smoke" stage (after cutting, effect "smoke"): surgical smoke. Each node a live hook
// coagulates this step (SimState::handoff.coagulated; not the nodes a cut adds, which take their
// parents' marks) raises a puff there, at most kPuffsPerStep a step; a puff rises against gravity
// at kRiseMps, drifts sideways, swells from kStartRadiusM by kGrowMps and thins out over kLifeS,
// then clears. At most kMaxPuffs live at once (the oldest gives way), held in storage sized once,
// so a step allocates nothing. It publishes SimState::handoff.smoke for the view.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "engine/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"

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
  void save(StateWriter& out) const override;
  void restore(StateReader& in, SimState& state) override;

 private:
  // One puff, every field 8 bytes (the snapshot writes the array as it is).
  struct Puff {
    std::array<double, 3> at{};     // centre, m
    std::array<double, 2> drift{};  // sideways velocity in the plane across gravity, m/s
    double born_s = -1.0;           // when it rose, s; < 0: none
  };
  void emit(const Vec3& at, double t);
  void publish(double t, SimState& state) const;

  Vec3 m_up;                         // unit, against gravity
  Vec3 m_side1, m_side2;             // unit, across it
  std::vector<Puff> m_puffs;         // (kMaxPuffs) a ring
  std::uint64_t m_next = 0;          // puffs raised so far (the ring's next slot, modulo)
  std::vector<std::uint8_t> m_seen;  // (n) coagulated marks already smoked
};

}  // namespace serosa::cutting
