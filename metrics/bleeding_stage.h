// The "bleeding" stage (after metrics, effect "bleeding"): blood from each cut through the
// unsecured artery that the metrics stage found (SimState::handoff.bleeds). The cut end, carried
// by the mesh node nearest where it was cut, bleeds in pulses at kHeartRateHz, kFlowM3PerS on
// average, until a ligature (clip, loop or staple line) placed since reaches within kClosedByM of
// it or the hook coagulates another node that near (a hook's own cut through the artery, which
// coagulates as it divides and on for kOwnStrokeS, does not close it); the blood pools where it
// falls (along gravity onto the first [[support]] plane, or under the cut end when there is none)
// as a film kPoolDepthM deep, up to kMaxPoolRadiusM across, and stains every node the pool reaches,
// for good. It publishes SimState::handoff.blood (one per bleeding) and handoff.stain (per node)
// for the view.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "engine/math.h"
#include "engine/scene.h"
#include "engine/sim_state.h"
#include "engine/stage.h"

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
  void save(StateWriter& out) const override;
  void restore(StateReader& in, SimState& state) override;

  /// The stream's strength at time t of a bleeding that began at since, [0, 1]: a systolic
  /// pulse over a steady ooze.
  [[nodiscard]] static double pulse(double t, double since);

 private:
  // One bleeding: every field 8 bytes (the snapshot writes the array as it is).
  struct Source {
    std::int64_t node = 0;                // the mesh node carrying the cut end
    double since_s = 0.0;                 // when it began, s
    double shed_m3 = 0.0;                 // blood shed so far, m^3
    double closed_s = -1.0;               // when it was closed, s; < 0: still bleeding
    std::array<double, 3> pool{};         // the pool's centre, m
    std::array<double, 3> pool_normal{};  // unit
    std::int64_t coagulated_near = 0;     // coagulated nodes near the cut end when it began
  };
  void begin(const Vec3& where, double since, const SimState& state);
  [[nodiscard]] bool closed(const Source& s, const SimState& state) const;
  [[nodiscard]] static std::int64_t coagulated_near(const Vec3& end, const SimState& state);
  void stain(const Source& s, double radius, const SimState& state);
  void publish(double time_s, SimState& state) const;

  Vec3 m_down;                     // unit, along gravity
  std::optional<Support> m_floor;  // where the blood pools
  std::vector<Source> m_sources;   // (bleedings) in the order they began
  std::vector<float> m_stain;      // (n) [0, 1]
};

}  // namespace serosa::metrics
