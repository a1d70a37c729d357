// snap_cut: the node-snapping baseline. The nodes nearest the blade are moved
// onto its plane, then the mesh is separated along the faces that now lie in the plane within the
// polygon. Same interface as cut_mesh (a CutResult whose TopologyDelta engine's apply()
// performs); no tet is subdivided, so the tet count never changes.
//
// How a move is expressed. A TopologyDelta cannot move an existing node (engine/topology_delta.h
// only adds nodes, adds and removes tets). A snapped node n therefore becomes a NEW node (or two,
// one per side, when the crack opens there) whose parents are the crossing edge (n, m) it slid
// along, weights (1 - s, s): rest, current position and velocity follow by the same weights, as
// for every other new node. Every tet around n is removed and re-added with the new node, in the
// same slot; n itself stays in the mesh, used by no tet (FEM gives it no stiffness). So no engine
// change was needed.
//
// Algorithm (current positions x; tol = classify_rel * h, h the longest edge near the blade):
//   1. Crossing edges: edges with one node above the plane and one below (beyond tol) whose
//      crossing point lies in the polygon (grown by tol).
//   2. Snapping, greedy: for each crossing edge its endpoint nearer the plane (ties: the positive
//      one) slides along one of its still-crossing edges (the shortest move) onto the plane.
//      Boundary nodes slide only along boundary edges, so they stay on the old surface's edges;
//      fixed nodes never move. A move is taken only when every tet around the node keeps a
//      mean-ratio quality >= min(min_quality, its quality before), in rest and in current
//      positions (so volumes stay positive). Crossing edges left with neither end moved then try
//      their other endpoint; edges still crossing after that are "unresolved" (the crack stays
//      welded there and the tets holding them straddle the plane).
//   3. Separation: a node on the plane (moved, or within tol) inside the polygon whose tets lie on
//      both sides and none straddles gets a second copy; the negative side keeps the first (the
//      original node for an unmoved one, as in the pattern method), the positive side uses the
//      copy. Faces in the plane whose three nodes are split open.
// What it does not keep: volume in general (a moved boundary node changes the surface; interior
// moves keep the total), per-group volume at group interfaces, the exact blade path (the crack
// follows mesh faces, up to half an edge from the blade), and element quality (the floor above).
#pragma once

#include <cstdint>

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting {

struct SnapOptions {
  /// Classification tolerance relative to the local edge length (as CutOptions::classify_rel).
  double classify_rel = 1e-6;
  /// Mean-ratio quality floor for the tets around a moved node (engine/mesh_quality.h), in rest
  /// and current positions; a tet already below it may not get worse. Dimensionless, in (0, 1).
  double min_quality = 0.05;
};

/// What snap_cut did beyond CutStats.
struct SnapStats {
  std::int64_t crossing_edges = 0;    ///< edges crossing the plane inside the polygon
  std::int64_t nodes_snapped = 0;     ///< nodes moved onto the plane
  std::int64_t snaps_refused = 0;     ///< moves refused by the quality floor (or a fixed node)
  std::int64_t edges_unresolved = 0;  ///< crossing edges with neither end moved (crack welded)
  std::int64_t nodes_split = 0;       ///< on-plane nodes given a second copy (crack opened)
  double max_move_m = 0.0;            ///< longest move of a snapped node, m
};

/// Cuts `mesh` by `blade` by node snapping (see above). CutStats: candidates, tets_removed =
/// tets_added (re-emitted tets), nodes_added, clones (= SnapStats::nodes_split), tolerance_m.
/// `query` finds candidate tets (a BVH; brute force when empty); `snap` receives the extra counts.
[[nodiscard]] CutResult snap_cut(const TetMesh& mesh, const ConvexPolygon& blade,
                                 const SnapOptions& options = {}, const TetBoxQuery& query = {},
                                 SnapStats* snap = nullptr);

}  // namespace serosa::cutting
