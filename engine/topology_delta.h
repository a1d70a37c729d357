// TopologyDelta: what one topology change did, so that every consumer (FEM, surface, render)
// updates itself incrementally instead of rebuilding (docs/ARCHITECTURE.md "Data model").
#pragma once

#include <cstdint>
#include <vector>

#include "engine/math.h"

namespace serosa {

struct TetMesh;

/// Where a new node came from: a point on an existing edge (2 parents), face (3) or inside a tet
/// (4), or a clone of an existing node (1). Rest position, current position and velocity of the
/// new node are the weighted sums of its parents' (weights sum to 1).
struct NodeParent {
  std::array<std::int32_t, 4> nodes{-1, -1, -1, -1};  ///< parent node ids; the first `count` used
  std::array<double, 4> weights{0.0, 0.0, 0.0, 0.0};  ///< barycentric weights, sum 1
  std::uint8_t count = 0;                             ///< 1 clone, 2 edge, 3 face, 4 interior
};

/// One topology change. Indices in `removed_tets` and `parents` refer to the mesh *before* the
/// change. Applying it (apply() below) is canonical for every consumer:
///   1. new nodes are appended in order: node ids n_old, n_old+1, ...;
///   2. the slots of removed tets (in ascending order) are reused by the added tets in order;
///   3. added tets left over are appended at the end;
///   4. removed slots left over are filled by moving the last tets down; each such move is listed
///      in `moved_tets` as (from, to), in the order performed (a tet may move twice), so consumers
///      relabel per-tet data by replaying the moves in order.
/// So after the change, tet id `slot_of_added[k]` holds added tet k.
struct TopologyDelta {
  std::vector<std::int32_t> removed_tets;   ///< (r) old tet ids, sorted ascending, unique
  std::vector<Tet> added_tets;              ///< (a) node ids in the new numbering
  std::vector<std::uint16_t> added_groups;  ///< (a) group of each added tet
  std::vector<NodeParent> added_nodes;      ///< (k) parents of each new node
  // ---- filled by apply() ----
  std::vector<std::int32_t> slot_of_added;                        ///< (a) tet id of each added tet
  std::vector<std::pair<std::int32_t, std::int32_t>> moved_tets;  ///< (from, to) relabels
  std::uint64_t version_before = 0;  ///< topology_version of the mesh it was applied to
  std::uint64_t version_after = 0;   ///< topology_version after applying it

  [[nodiscard]] bool empty() const {
    return removed_tets.empty() && added_tets.empty() && added_nodes.empty();
  }
};

/// Applies `delta` to `mesh` (rules above), interpolating rest, x and v of new nodes from their
/// parents (mass 0, free: FEM assigns mass), and bumps topology_version. Fills the "filled by
/// apply" fields of `delta`. Throws std::invalid_argument on an inconsistent delta (ids out of
/// range, unsorted removals, mismatched sizes), leaving the mesh unchanged.
void apply(TetMesh& mesh, TopologyDelta& delta);

}  // namespace serosa
