// SimState: everything that changes while a scene runs (docs/ARCHITECTURE.md "State").
#pragma once

#include <cstdint>
#include <vector>

#include "engine/tet_mesh.h"
#include "engine/tool_state.h"

namespace serosa {

/// The mutable state of a running scene. The scene model (engine/scene.h) is read-only after load;
/// this is what stages write. Copyable: snapshots, tests and benchmarks copy it.
struct SimState {
  double time_s = 0.0;           ///< simulated time, s
  std::uint64_t step = 0;        ///< solver steps taken
  TetMesh mesh;                  ///< all organs of the scene in one mesh (groups tell them apart)
  std::vector<ToolState> tools;  ///< (tools) latest consumed input per scene tool, scene order
};

/// 64-bit FNV-1a hash of the state: time, step, topology, positions and velocities, tool inputs.
/// Equal states (bit for bit) give equal hashes; used by recordings and regression reports.
[[nodiscard]] std::uint64_t state_hash(const SimState& s);

}  // namespace serosa
