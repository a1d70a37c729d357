// The "bleeding" stage (after metrics, effect "bleeding"): blood from each cut through the
// unsecured artery that the metrics stage found (SimState::shared.bleeds). The cut end, carried
// by the mesh node nearest where it was cut, bleeds in pulses at kHeartRateHz, kFlowM3PerS on
// average, until a ligature (clip, loop or staple line) placed since reaches within kClosedByM of
// it or the hook coagulates another node that near (a hook's own cut through the artery, which
// coagulates as it divides and on for kOwnStrokeS, does not close it); the blood pools where it
// falls (along gravity onto the first [[support]] plane, or under the cut end when there is none)
// as a film kPoolDepthM deep, up to kMaxPoolRadiusM across, and stains every node the pool reaches,
// for good. It publishes SimState::shared.blood (one per bleeding) and blocks.bleeding.stain (per
// node) for the view.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "engine/scene/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"
#include "engine/state_blocks.h"

namespace serosa::metrics {

class BleedingStage final : public Stage {
 public:
  static constexpr double kFlowM3PerS = 2e-6;      ///< mean arterial flow from the cut end (2 mL/s)
  static constexpr double kHeartRateHz = 1.25;     ///< pulses per second (75 a minute)
  static constexpr double kPoolDepthM = 0.003;     ///< the pool's film depth, m
  static constexpr double kMaxPoolRadiusM = 0.04;  ///< the pool spreads no further, m
  static constexpr double kClosedByM = 0.004;  ///< a ligature or coagulation this near closes it
  /// Coagulation in this long after the bleeding began is the cutting stroke's own, s.
  static constexpr double kOwnStrokeS = 0.5;

  explicit BleedingStage(const Scene& scene);
  [[nodiscard]] std::string_view name() const noexcept override { return "bleeding"; }
  void step(const StepContext& ctx, SimState& state) override;
  void adopt(SimState& state) override;

  /// The stream's strength at time t of a bleeding that began at since, [0, 1]: a systolic
  /// pulse over a steady ooze.
  [[nodiscard]] static double pulse(double t, double since);

 private:
  using Source = BleedingBlock::Source;
  void begin(const Vec3& where, double since, SimState& state) const;
  [[nodiscard]] bool closed(const Source& s, const SimState& state) const;
  [[nodiscard]] static std::int64_t coagulated_near(const Vec3& end, const SimState& state);
  static void stain(const Source& s, double radius, SimState& state);
  static void publish(double time_s, SimState& state);

  Vec3 m_down;                     // unit, along gravity
  std::optional<Support> m_floor;  // where the blood pools
};

}  // namespace serosa::metrics
