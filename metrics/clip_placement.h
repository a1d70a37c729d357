// Where the clip applier's clips went (the clip-application drill, the procedure's first
// securing). Looked at every step from the placed clips (SimState::shared.clips):
//   clips_on_artery       clips that clamp some of the artery, 1
//   clips_off_artery      clips closed on tissue but none of the artery (a wasted clip on the fold,
//                         or worse, the bowel), 1
//   clip_target_error_m   with a clip target: the rest distance from it to the nearest clip on the
//                         artery (the mean rest position of the nodes the clip clamps), m; +inf
//                         while no clip is on the artery (the report writes null)
// Endoloops are not clips: they are judged by the procedure's steps.
#pragma once

#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/bound_block.h"
#include "engine/clip.h"
#include "engine/math.h"
#include "engine/metrics_block.h"

namespace serosa::metrics {

class ClipPlacement {
 public:
  ClipPlacement() = default;
  /// artery: the artery's group id; target: where a clip should go, at rest, m.
  ClipPlacement(int artery, std::optional<Vec3> target)
      : m_on(true), m_artery(artery), m_target(target) {}

  [[nodiscard]] bool active() const noexcept { return m_on; }
  void step(const std::vector<Clip>& clips);

  [[nodiscard]] int on_artery() const noexcept { return m_b->on_artery; }
  [[nodiscard]] int off_artery() const noexcept { return m_b->off_artery; }
  [[nodiscard]] double target_error_m() const noexcept { return m_b->error; }

  /// metrics["clips"] = {"on_artery", "off_artery", "target_error_m" (with a target)}.
  void report(nlohmann::json& metrics) const;
  /// Reads and writes the SimState block `b` from now on (engine/bound_block.h).
  void bind(ClipPlacementBlock& b) noexcept { m_b.bind(b); }
  /// The zero block it starts a state's from.
  [[nodiscard]] const ClipPlacementBlock& unbound_block() const noexcept { return m_b.unbound(); }

 private:
  bool m_on = false;
  int m_artery = -1;
  std::optional<Vec3> m_target;
  BoundBlock<ClipPlacementBlock> m_b;  // its block of the state
};

}  // namespace serosa::metrics
