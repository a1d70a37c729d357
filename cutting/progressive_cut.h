// ProgressiveCut: one scissors stroke cut while it progresses (Mor & Kanade 2000, "progressive
// cutting"), so that a stroke of many thin steps ends as the one cut of everything it swept.
//
// Cutting each step's thin polygon into the mesh the earlier steps made (cut_mesh alone) fails on
// thin steps off the grid planes: a step a fraction of a tet wide crosses tets as strips or
// grazes them, so cut_mesh opens them short of the blade or not at all, and no later step covers
// that part of the blade again: the crack keeps welded gaps and the organ does not come apart. The
// pieces ahead of each step's crack front are split again by the next step, so the mesh grows
// geometrically with the steps (docs/BENCHMARKS.md "Cutting", mesh growth).
//
// A ProgressiveCut remembers, for the stroke under way, the region swept so far (a convex
// polygon), the tets of the mesh as it was before the stroke that the stroke replaced
// ("originals") and the ids of the pieces standing in for them now. A step whose polygon lies in
// the stroke's plane and whose union with the region is convex (the next thin triangle of a
// closing scissors, the next quad of a blade pushed along a line) extends the region, and the
// step's delta replaces the stroke's pieces by the pieces of the originals (and of every other
// tet the larger region reaches) cut by the whole region: the earlier steps' pieces are never cut
// again. So after every step the mesh is the mesh before the stroke cut once by the region swept
// so far (up to node numbering and the quad diagonals that follow it): the crack covers the whole
// swept region with no pins a thin step would leave, on static tissue the tets created do not
// depend on how finely the stroke was stepped, and cut_mesh's invariants hold step by step
// (check_cut of the pre-stroke mesh against the region).
//
// The price: every step re-cuts the whole region (time grows with the stroke, not the step), and
// the nodes of the previous step's pieces are released (left in no tet; FEM keeps released nodes
// still and massless) in favour of new ones interpolated from the originals' nodes where they are
// now. The region is fixed in space and the originals are re-cut in their current positions: if
// the tissue moves during the stroke, the earlier part of the crack is re-made where the region
// meets the tissue now (not where it met it then), the crack's opening and its nodes' velocities
// are reset to the originals' affine motion at every step, and the count of tets created is that
// of one cut of the moved mesh. That suits a blade closing in a fraction of a second over tissue
// that barely moves; for tissue that drifts, end() the stroke. A polygon off the stroke's plane,
// or whose union with the region is not convex, or any topology change not made by this object in
// between (another cut, another tool), ends the stroke: the step then begins a new one from the
// mesh as it is.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {

/// What the last ProgressiveCut::cut did besides the cut itself.
struct StrokeStep {
  bool extended = false;  ///< the polygon extended the stroke under way (else it began one)
  bool inside = false;    ///< the polygon lay inside the region already cut: empty delta
  std::int64_t pieces_replaced = 0;     ///< stroke pieces the delta removes
  std::int64_t originals_restored = 0;  ///< originals the larger region no longer cuts, put back
  std::int64_t nodes_released = 0;      ///< stroke nodes the delta leaves in no tet
};

/// Merges polygon b into region a: the convex polygon a ∪ b, oriented like a, when b lies in a's
/// plane (every corner within plane_rel * the pair's size) and a ∪ b is convex (the hull's area
/// exceeds a's + b's − their overlap's by at most area_rel of it). std::nullopt otherwise.
[[nodiscard]] std::optional<ConvexPolygon> convex_union(const ConvexPolygon& a,
                                                        const ConvexPolygon& b,
                                                        double plane_rel = 1e-9,
                                                        double area_rel = 1e-9);

class ProgressiveCut {
 public:
  explicit ProgressiveCut(CutOptions options = {}) : m_options(options) {}

  /// The next polygon of the stroke. Returns the change to `mesh` (apply() it, then call
  /// applied()): the stroke's pieces replaced by the cut, by region(), of the mesh before the
  /// stroke. stats are that cut's (counts over the mesh before the stroke plus the tets the
  /// region newly reaches); the delta's own sizes are its removed/added lists. `query` finds
  /// candidate tets of `mesh` (brute force when empty); the stroke's originals are added to them.
  [[nodiscard]] CutResult cut(const TetMesh& mesh, const ConvexPolygon& blade,
                              const TetBoxQuery& query = {});

  /// Records that the delta the last cut() returned was applied to `mesh` (its filled-in
  /// slot_of_added locate the stroke's new pieces). A delta that is not that one (other sizes, or
  /// made against another topology version) ends the stroke. Without this call the step is
  /// forgotten: the next cut() goes on from the stroke as it was if the mesh did not change, and
  /// begins a new stroke if it did (the step's delta applied).
  void applied(const TetMesh& mesh, const TopologyDelta& delta);

  /// Ends the stroke: the next cut() begins a new one from the mesh as it is then.
  void end();

  [[nodiscard]] bool active() const { return m_region.has_value(); }
  /// The region the stroke has cut so far (after applied()); std::nullopt between strokes.
  [[nodiscard]] const std::optional<ConvexPolygon>& region() const { return m_region; }
  [[nodiscard]] const StrokeStep& last_step() const { return m_last; }
  /// Tets standing in the mesh for the stroke's originals (the pieces of one cut by region()).
  [[nodiscard]] std::size_t num_pieces() const { return m_pieces.size(); }
  [[nodiscard]] const CutOptions& options() const { return m_options; }

 private:
  struct Original {
    Tet tet{};  ///< node ids (nodes of the mesh before the stroke)
    std::uint16_t group = 0;
  };
  struct Pending {
    std::optional<ConvexPolygon> region;
    std::vector<Original> originals;
    std::size_t pieces = 0;     ///< the delta's first `pieces` added tets are the stroke's pieces
    std::int32_t nodes = 0;     ///< the stroke's nodes after the step (the delta's new nodes)
    bool keep = false;          ///< nothing changed: keep the stroke as it is
    std::uint64_t version = 0;  ///< mesh topology_version the delta was made against
    std::size_t removed = 0;    ///< the delta's sizes (applied() recognises it by them)
    std::size_t added = 0;
    double tolerance_m = 0.0;
  };

  /// The mesh before the stroke around the region, in local numbering.
  struct LocalRegion {
    TetMesh mesh;
    std::vector<std::int32_t> origin;     ///< local tet -> tet of the mesh, or -1 - original index
    std::vector<std::int32_t> global_of;  ///< local node -> node of the mesh, ascending
  };
  CutResult start_stroke(const TetMesh& mesh, const ConvexPolygon& region, const TetBoxQuery& q);
  [[nodiscard]] bool is_piece(std::int32_t t) const;
  /// (tolerance, longest edge it is relative to), m.
  [[nodiscard]] std::pair<double, double> stroke_tolerance(const TetMesh& mesh,
                                                           const ConvexPolygon& region,
                                                           const TetBoxQuery& q) const;
  [[nodiscard]] LocalRegion pre_stroke_region(const TetMesh& mesh, const ConvexPolygon& region,
                                              const TetBoxQuery& q, double tol, double h) const;
  CutResult compose(const TetMesh& mesh, const ConvexPolygon& region, const LocalRegion& local,
                    CutResult lr);

  CutOptions m_options;
  std::optional<ConvexPolygon> m_region;  ///< swept so far
  std::vector<Original> m_originals;      ///< tets of the mesh before the stroke now in pieces
  std::vector<std::int32_t> m_pieces;     ///< (sorted) tet ids of the stroke's pieces now
  std::int32_t m_nodes = 0;               ///< nodes the stroke's pieces brought in
  std::uint64_t m_version = 0;            ///< mesh topology_version after the last step
  double m_tolerance = 0.0;               ///< classification tolerance of the last step, m
  std::optional<Pending> m_pending;
  StrokeStep m_last;
};

}  // namespace serosa::cutting
