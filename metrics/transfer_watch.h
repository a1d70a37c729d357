// The grasp-and-transfer drill (after FLS's peg transfer): an object is picked up with one
// grasper, handed to the other in the air and set down on a target. Looked at every step from
// the grasps (SimState::shared.grasped) and the object's nodes:
//   transfer.handoffs           times the object passed from one grasper to another without
//                               being let go in between (both held it, then the first let go), 1
//   transfer.drops              times every grasper let go of it away from the target (beyond
//                               `radius` of it across the board), 1
//   transfer.placed             1 when the object lies on the target, held by no grasper: its
//                               centre within `radius` of the target across the board and no
//                               more than `radius` above it; else 0
//   transfer.placement_error_m  the object's centre's distance from the target across the board
//                               now, m
// "Across the board": in the plane normal to `up` (the board's normal). The object's centre is
// the mean of its nodes' positions.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/bound_block.h"
#include "engine/math.h"
#include "engine/metrics_block.h"
#include "engine/sim_state.h"

namespace serosa::metrics {

class TransferWatch {
 public:
  TransferWatch() = default;
  /// group: the object's group id; target (m), radius (m, > 0), up (unit): the board's.
  TransferWatch(int group, Vec3 target, double radius, Vec3 up);

  [[nodiscard]] bool active() const noexcept { return m_on; }
  /// Looks at the end of a solver step (time_s).
  void step(double time_s, const SimState& state);

  [[nodiscard]] int handoffs() const noexcept { return m_b->handoffs; }
  [[nodiscard]] int drops() const noexcept { return m_b->drops; }
  [[nodiscard]] bool placed() const;
  [[nodiscard]] double error_m() const { return across(m_b->centre - m_target).norm(); }

  /// metrics["transfer"] = {"handoffs", "drops", "drop_times_s", "placed",
  /// "placement_error_m"}.
  void report(nlohmann::json& metrics) const;
  /// Reads and writes the SimState block `b` from now on (engine/bound_block.h).
  void bind(TransferBlock& b) noexcept { m_b.bind(b); }
  /// The bound block was restored: drops the caches taken from the mesh.
  void adopt() noexcept { m_version = ~0ull; }
  /// The zero block it starts a state's from.
  [[nodiscard]] const TransferBlock& unbound_block() const noexcept { return m_b.unbound(); }

 private:
  [[nodiscard]] Vec3 across(const Vec3& d) const { return d - d.dot(m_up) * m_up; }
  void refresh_nodes(const TetMesh& mesh);
  /// The graspers holding some of the object now (tool indices, ascending).
  void find_holders(const SimState& state, std::vector<std::int64_t>& out) const;

  bool m_on = false;
  int m_group = -1;
  Vec3 m_target = Vec3::Zero(), m_up = Vec3::UnitZ();
  double m_radius = 0.0;
  // Caches (rebuilt after a restore: adopt()):
  std::uint64_t m_version = ~0ull;
  std::vector<std::uint8_t> m_in_object;  // (n) 1: a node of the object
  std::vector<std::int32_t> m_nodes;      // the object's nodes
  std::vector<std::int64_t> m_now;        // scratch: this step's holders
  BoundBlock<TransferBlock> m_b;          // its block of the state
};

}  // namespace serosa::metrics
