#include "cutting/cut_emit_tet.h"

#include <algorithm>
#include <cmath>

namespace serosa::cutting::detail {

std::int32_t edge_point_id(CutState& cs, std::int32_t a, std::int32_t b, bool pos, Combo& combo) {
  const std::int32_t lo = std::min(a, b), hi = std::max(a, b);
  const EdgeInfo& e = cs.edges.at(edge_key(a, b));
  combo.add(lo, 1.0 - e.t);
  combo.add(hi, e.t);
  const EdgePair pair = cs.weld.edge_point(a, b, e.t, e.open);
  return pos ? pair.pos : pair.neg;
}

void emit_tet(CutState& cs, std::array<std::int32_t, 4> ids,
              const std::array<const Combo*, 4>& combos, std::uint16_t g) {
  const double vol = signed_volume(combos[0]->rest(cs.mesh), combos[1]->rest(cs.mesh),
                                   combos[2]->rest(cs.mesh), combos[3]->rest(cs.mesh));
  if (vol < 0.0) std::swap(ids[2], ids[3]);
  if (!(std::abs(vol) > 0.0)) ++cs.result.stats.degenerate_tets;
  cs.result.delta.added_tets.push_back({ids[0], ids[1], ids[2], ids[3]});
  cs.result.delta.added_groups.push_back(g);
}

}  // namespace serosa::cutting::detail
