#include "engine/sim_state.h"

#include <cstring>

namespace serosa {
namespace {

struct Fnv1a {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= c[i];
      h *= 1099511628211ull;
    }
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    const std::uint64_t n = v.size();
    bytes(&n, sizeof n);
    if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
  }
};

}  // namespace

std::uint64_t state_hash(const SimState& s) {
  Fnv1a f;
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
  f.vec(s.handoff.external_force_n);
  f.vec(s.handoff.tool_force_n);
  return f.h;
}

}  // namespace serosa
