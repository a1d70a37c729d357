#include "engine/sim_state.h"

#include <cstring>

#include "engine/fnv1a.h"

namespace serosa {

std::uint64_t state_hash(const SimState& s) {
  // Not FNV's offset basis (a digit short), but every recording and golden carries hashes made
  // from it: kept.
  Fnv1a f{1469598103934665603ull};
  f.bytes(&s.time_s, sizeof s.time_s);
  f.bytes(&s.step, sizeof s.step);
  f.bytes(&s.mesh.topology_version, sizeof s.mesh.topology_version);
  f.vec(s.mesh.tets);
  f.vec(s.mesh.group);
  f.vec(s.mesh.x);
  f.vec(s.mesh.v);
  f.vec(s.mesh.fixed);  // grasp holds set and restore Dirichlet flags
  // Field by field: a ToolState has padding, whose bytes copies need not keep.
  for (const ToolState& t : s.tools) {
    f.bytes(&t.tick, sizeof t.tick);
    f.bytes(&t.time_s, sizeof t.time_s);
    f.bytes(t.tip_m.data(), sizeof t.tip_m);
    f.bytes(t.quat_wxyz.data(), sizeof t.quat_wxyz);
    f.bytes(&t.jaw_rad, sizeof t.jaw_rad);
    f.bytes(&t.buttons, sizeof t.buttons);
  }
  f.vec(s.events.external_force_n);
  f.vec(s.events.tool_force_n);
  return f.h;
}

}  // namespace serosa
