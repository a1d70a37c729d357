// Collision BVH over the surface triangles: closest point, ray and segment
// queries for the tools, in current positions.
//
// Design. A binary tree of axis-aligned boxes whose leaves hold surface face slots (indices into
// SurfaceMesh::faces). It stores node ids of each face (never positions: one set of nodes) and
// the boxes computed from the positions it was last fitted to.
//  - build(): top-down, median split of face centroids along the longest axis, up to 4 faces per
//    leaf. O(f log f). Children always have larger node indices than their parent.
//  - refit(): recomputes every box bottom-up from the current positions (leaves from their
//    faces, parents from children) in one reverse sweep over the nodes. O(f). Run every step.
//  - update(): after update_surface() reported the changed slots, a LOCAL update: each changed or
//    removed slot leaves its leaf (O(1) swap-remove), each changed or new slot is re-inserted
//    by descending from the root to the child whose box grows least (surface area), and a leaf
//    that grows past 8 faces is split in two at its centroid median (two new nodes appended).
//    No re-sort of the faces and no new tree: the work is O(k depth) for k changed slots, plus
//    one refit() (O(f), the same as every step's). The tree stays correct for any sequence of
//    updates (queries equal a rebuild's, tested); its quality slowly drifts after many cuts
//    (boxes larger, depth greater), so a caller may rebuild() when depth() has grown a lot.
//  - Queries take the positions the tree was last refitted to; their answers are exactly those of
//    a brute-force loop over all faces with the same primitive tests and the same tie rule (the
//    smaller slot wins on equal distance or t): boxes are padded so culling is conservative.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "engine/math.h"
#include "engine/surface_mesh.h"

namespace serosa::geometry {

/// Closest surface point to a query point.
struct ClosestHit {
  std::int32_t face = -1;     ///< SurfaceMesh face slot
  Vec3 point = Vec3::Zero();  ///< closest point, m
  Vec3 bary = Vec3::Zero();   ///< its barycentrics on faces[face] (corner order), sum 1
  double distance = 0.0;      ///< |query - point|, m
};

/// A ray or segment crossing a surface face.
struct RayHit {
  std::int32_t face = -1;    ///< SurfaceMesh face slot
  double t = 0.0;            ///< ray: origin + t dir; segment: a + t (b - a), t in [0, 1]
  Vec3 bary = Vec3::Zero();  ///< barycentrics of the hit on faces[face], sum 1
};

class SurfaceBvh {
 public:
  /// Full build over the faces of `s` in positions `x` ((n) TetMesh::x, m). O(f log f).
  /// Throws std::invalid_argument when a face names a node outside x.
  void build(const SurfaceMesh& s, std::span<const Vec3> x);

  /// Refits every box to positions `x` (same faces as the last build/update). O(f).
  void refit(std::span<const Vec3> x);

  /// Local update after update_surface(s, ..., &changed_slots) (see above): `s` is the updated
  /// surface, `changed_slots` what update_surface reported (any superset works: slots past the
  /// previous face count are treated as changed whether listed or not), `x` the positions.
  void update(const SurfaceMesh& s, std::span<const std::int32_t> changed_slots,
              std::span<const Vec3> x);

  /// The closest point of the surface to p within max_distance (m), or none.
  [[nodiscard]] std::optional<ClosestHit> closest_point(
      std::span<const Vec3> x, const Vec3& p,
      double max_distance = std::numeric_limits<double>::infinity()) const;

  /// First hit of the ray origin + t dir, t in [0, t_max] (dir need not be unit; t is in units
  /// of |dir|). Faces hit at equal t: the smaller slot.
  [[nodiscard]] std::optional<RayHit> raycast(
      std::span<const Vec3> x, const Vec3& origin, const Vec3& dir,
      double t_max = std::numeric_limits<double>::infinity()) const;

  /// First crossing of segment [a, b] (t in [0, 1]); none for a zero-length segment.
  [[nodiscard]] std::optional<RayHit> segment_first(std::span<const Vec3> x, const Vec3& a,
                                                    const Vec3& b) const;

  /// Every crossing of segment [a, b], sorted by (t, face); cleared first. None for a
  /// zero-length segment.
  void segment_all(std::span<const Vec3> x, const Vec3& a, const Vec3& b,
                   std::vector<RayHit>& hits) const;

  [[nodiscard]] std::int32_t num_faces() const { return static_cast<std::int32_t>(tris_.size()); }
  [[nodiscard]] std::int32_t num_nodes() const { return static_cast<std::int32_t>(nodes_.size()); }
  /// Longest root-to-leaf path (edges); grows with local updates.
  [[nodiscard]] std::int32_t depth() const;

 private:
  struct Node {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());  ///< box, m
    Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());
    std::int32_t child[2] = {-1, -1};  ///< internal node: children (larger indices)
    std::int32_t leaf = -1;            ///< leaf node: index into leaves_
  };

  std::int32_t build_range(std::vector<std::int32_t>& slots, std::size_t begin, std::size_t end,
                           std::span<const Vec3> x);
  std::int32_t make_leaf(std::span<const std::int32_t> slots);
  void remove_slot(std::int32_t slot);
  void insert_slot(std::int32_t slot, std::span<const Vec3> x);
  void split_leaf(std::int32_t node, std::span<const Vec3> x);
  void fit_leaf(Node& n, std::span<const Vec3> x) const;
  template <class Visit>
  void ray_traverse(std::span<const Vec3> x, const Vec3& o, const Vec3& d, double t_max,
                    Visit&& visit) const;

  std::vector<Node> nodes_;                        ///< node 0 is the root (when any)
  std::vector<std::vector<std::int32_t>> leaves_;  ///< slots of each leaf
  std::vector<Tri> tris_;                          ///< (f) node ids of each slot
  std::vector<std::int32_t> slot_node_;            ///< (f) leaf node holding each slot
  std::vector<std::int32_t> slot_pos_;             ///< (f) its position in that leaf
};

}  // namespace serosa::geometry
