// TetBvh: a bounding-volume hierarchy over the tets of a mesh in current positions, the
// candidate search of cut_mesh. Refitted between steps (same topology); updated locally after a
// cut (the cost follows the tets the cut touched, not the mesh size).
#pragma once

#include <cstdint>
#include <vector>

#include "cutting/cut_mesh.h"
#include "cutting/reserve.h"
#include "engine/math.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {

class TetBvh {
 public:
  /// Builds over the mesh's current positions x (median split on the widest axis of the tet
  /// centroids, up to 4 tets per leaf). O(m log m). The per-tet arrays and the node array get
  /// capacity for `spare` (fraction, >= 0) more tets and nodes than built, so the cuts after the
  /// build append to them without reallocating (untouched capacity costs no page faults). A copy
  /// of a TetBvh has no spare capacity (std::vector copies do not keep it). Throws
  /// std::invalid_argument when spare is negative or not finite.
  explicit TetBvh(const TetMesh& mesh, double spare = kCutSpare);

  /// Recomputes every box for moved nodes (same tets as at build or last update). O(m). Throws
  /// std::invalid_argument when the tet count differs (a cut was applied without update()).
  void refit(const TetMesh& mesh);

  /// Follows one applied cut: `mesh` is the mesh after apply(mesh, delta), `delta` the delta
  /// apply() filled (slot_of_added, moved_tets). Boxes of the changed tets are set, new tets go
  /// into the leaf their box grows least (a leaf over 8 tets splits), moved tets keep their
  /// leaf under their new id, and only the changed leaves and their ancestors are refitted:
  /// O(changed tets x depth), independent of the mesh size. Depth stays bounded: when a leaf
  /// gets deeper than max_depth() the highest unbalanced ancestor on its path (a child holding
  /// over 3/4 of its tets, as in a scapegoat tree) is rebuilt by median splits, an amortised
  /// O(log m) per inserted tet; nodes orphaned by rebuilds are reclaimed by a full rebuild once
  /// they outnumber the live ones. Throws std::invalid_argument when the delta does not match
  /// (the BVH must be at delta.version_before's tet count).
  void update(const TetMesh& mesh, const TopologyDelta& delta);

  /// Appends the ids of exactly the tets whose boxes meet [lo, hi] (m), as brute_force_query.
  void query(const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) const;

  /// This BVH as cut_mesh's candidate search (the BVH must outlive the returned function).
  [[nodiscard]] TetBoxQuery as_query() const;

  [[nodiscard]] std::int32_t num_tets() const { return static_cast<std::int32_t>(m_lo.size()); }
  /// Depth of the deepest leaf (root = 0); for tests and benchmarks. O(nodes).
  [[nodiscard]] std::int32_t depth() const;
  /// The bound update() keeps depth() under: 2 ceil(log2(m / 4 + 1)) + 2, m the tet count.
  [[nodiscard]] std::int32_t max_depth() const;
  /// Subtree rebuilds update() has done since construction (for tests and benchmarks).
  [[nodiscard]] std::int64_t rebuilds() const { return m_rebuilds; }

 private:
  struct Node {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    std::int32_t left = -1;  ///< inner: children (leaf: -1)
    std::int32_t right = -1;
    std::int32_t parent = -1;
    std::int32_t size = 0;           ///< tets in the subtree
    std::int32_t depth = 0;          ///< root = 0
    std::vector<std::int32_t> tets;  ///< leaf: tet ids
  };
  struct Item {
    Vec3 c = Vec3::Zero();  ///< centroid, m
    std::int32_t tet = -1;
  };
  std::int32_t build(std::vector<Item>& items, std::int32_t begin, std::int32_t end,
                     std::int32_t parent, std::int32_t depth);
  void set_box(const TetMesh& mesh, std::int32_t tet);
  void refit_leaf(std::int32_t node);
  void refit_up(std::int32_t node);
  void split_leaf(const TetMesh& mesh, std::int32_t node);
  std::int32_t choose_leaf(std::int32_t tet) const;
  void remove_from_leaf(std::int32_t tet);
  void add_size(std::int32_t node, std::int32_t delta);
  void rebalance(const TetMesh& mesh, std::int32_t leaf);
  void rebuild_subtree(const TetMesh& mesh, std::int32_t node);
  void collect(std::int32_t node, std::vector<std::int32_t>& tets) const;

  std::vector<Node> m_nodes;            ///< children always after their parent
  std::vector<Vec3> m_lo, m_hi;         ///< (m) box of each tet, m
  std::vector<std::int32_t> m_leaf_of;  ///< (m) leaf node holding each tet
  std::int64_t m_orphans = 0;           ///< nodes no longer reachable (left by rebuilds)
  std::int64_t m_rebuilds = 0;
  double m_spare = kCutSpare;  ///< spare capacity fraction, kept by full rebuilds
};

}  // namespace serosa::cutting
