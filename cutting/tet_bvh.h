// TetBvh: a bounding-volume hierarchy over the tets of a mesh in current positions, the
// candidate search of cut_mesh. Refitted between steps (same topology); rebuilt after a cut.
#pragma once

#include <cstdint>
#include <vector>

#include "cutting/cut_mesh.h"
#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting {

class TetBvh {
 public:
  /// Builds over the mesh's current positions x (median split on the widest axis of the tet
  /// centroids, up to 4 tets per leaf). O(m log m).
  explicit TetBvh(const TetMesh& mesh);

  /// Recomputes every box for moved nodes (same tets as at build). O(m). Throws
  /// std::invalid_argument when the tet count changed (a cut happened: rebuild instead).
  void refit(const TetMesh& mesh);

  /// Appends the ids of exactly the tets whose boxes meet [lo, hi] (m), as brute_force_query.
  void query(const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out) const;

  /// This BVH as cut_mesh's candidate search (the BVH must outlive the returned function).
  [[nodiscard]] TetBoxQuery as_query() const;

  [[nodiscard]] std::int32_t num_tets() const { return static_cast<std::int32_t>(m_order.size()); }

 private:
  struct Node {
    Vec3 lo, hi;
    std::int32_t first = 0;   ///< leaf: first index into m_order; inner: left child
    std::int32_t count = 0;   ///< leaf: number of tets; inner: 0
    std::int32_t right = -1;  ///< inner: right child
  };
  std::int32_t build(const TetMesh& mesh, std::vector<Vec3>& centroids, std::int32_t begin,
                     std::int32_t end);

  std::vector<Node> m_nodes;          ///< preorder: children after their parent
  std::vector<std::int32_t> m_order;  ///< (m) tet ids, leaves' ranges
  std::vector<Vec3> m_lo, m_hi;       ///< (m) box of the tet at each m_order slot, m
};

}  // namespace serosa::cutting
