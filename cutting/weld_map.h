// WeldMap: the new nodes one cut creates, shared between neighbouring tets so the result is
// welded. Edge points come in pairs (one per side) keyed by the cut edge; clones of coplanar
// nodes keyed by the node; Steiner points are private to one prism.
#pragma once

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "engine/topology_delta.h"

namespace serosa::cutting {

/// The nodes created on a cut edge: same position, one for each side of the cut; an edge that
/// is split but not opened (welded) has a single node, pos == neg.
struct EdgePair {
  std::int32_t pos = -1;  ///< used by the pieces on the positive side
  std::int32_t neg = -1;  ///< used by the pieces on the negative side
};

/// Key of the undirected edge (a, b): smaller id in the high 32 bits.
[[nodiscard]] inline std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint32_t>(a < b ? a : b);
  const auto hi = static_cast<std::uint32_t>(a < b ? b : a);
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

class WeldMap {
 public:
  /// @param first_new_id the id the first new node gets (the mesh's node count)
  explicit WeldMap(std::int32_t first_new_id) : m_next(first_new_id) {}

  /// The node(s) on edge (a, b) at parameter t measured from min(a, b) to max(a, b), created on
  /// the first request: two when `open`, one (pos == neg) otherwise. Later requests return the
  /// same nodes (t and open are then ignored: callers decide both per edge, once).
  EdgePair edge_point(std::int32_t a, std::int32_t b, double t_from_lo, bool open);
  /// The clone of original node a (created on the first request).
  std::int32_t clone(std::int32_t a);
  /// The clone of a if one was created.
  [[nodiscard]] std::optional<std::int32_t> find_clone(std::int32_t a) const;
  /// A node private to the caller (a Steiner point), from its parents.
  std::int32_t add_point(const NodeParent& parent);

  /// Parents of every new node, in id order (ids first_new_id, first_new_id + 1, ...).
  [[nodiscard]] const std::vector<NodeParent>& new_nodes() const { return m_new; }
  [[nodiscard]] std::vector<NodeParent> take_new_nodes() { return std::move(m_new); }
  /// Edges given two nodes / one node.
  [[nodiscard]] std::int64_t edge_pairs() const { return m_pairs; }
  [[nodiscard]] std::int64_t edge_singles() const {
    return static_cast<std::int64_t>(m_edges.size()) - m_pairs;
  }
  [[nodiscard]] std::int64_t clones() const { return static_cast<std::int64_t>(m_clones.size()); }

 private:
  std::int32_t push(const NodeParent& p);

  std::int32_t m_next;
  std::int64_t m_pairs = 0;
  std::vector<NodeParent> m_new;
  std::unordered_map<std::uint64_t, EdgePair> m_edges;
  std::unordered_map<std::int32_t, std::int32_t> m_clones;
};

}  // namespace serosa::cutting
