// What a cut takes and gives (cutting/cut_mesh.h): its options, its statistics, its result, and
// how it finds the tets a blade may meet. In a header of their own so that the cut's steps share
// them without including the cut itself.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "cutting/case_table.h"
#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"

namespace serosa::cutting {

struct CutOptions {
  /// Classification tolerance relative to the local edge length: a node within
  /// classify_rel * h of the plane is on it (sign 0), where h is the longest edge of the tets
  /// whose boxes meet the blade's box. Also the in-plane tolerance of "inside the polygon".
  double classify_rel = 1e-6;
  /// When > 0: the classification tolerance itself (m), instead of classify_rel * h
  /// (ProgressiveCut re-cuts a local mesh with the tolerance of the whole mesh). cut_mesh only:
  /// the removal and snapping baselines always use classify_rel * h.
  double tolerance_m = 0.0;
  /// Second pass (docs/cutting.md, point 7): a pinned tet, or a partial tet whose crack
  /// would miss part of the blade's share of its section, is coned from a point inside that
  /// share, and the pieces are cut again by the same blade. On 153 random blades about a tet
  /// wide the crack then covers 99.6 % of the blade's area on average instead of 60 %, and 147
  /// open exactly instead of 42, but the mesh gets more and thinner tets (docs/BENCHMARKS.md
  /// "Cutting", second pass): off by default.
  bool reopen_pinned = false;
};

/// What a cut did. Counts are over the tets and nodes of the mesh before the cut.
struct CutStats {
  std::int64_t candidates = 0;       ///< tets whose box met the blade's (grown) box
  std::int64_t tets_split = 0;       ///< tets subdivided by a complete-cut pattern
  std::int64_t tets_relabelled = 0;  ///< one-sided tets that took a clone of a coplanar node
  std::int64_t tets_partial = 0;     ///< tets the blade's outline crosses: cut up to it, coned
  /// Of those, split welded with their edges and nodes welded in their neighbours too: the
  /// crack stops before them (docs/cutting.md, point 5).
  std::int64_t tets_pinned = 0;
  std::int64_t pinned_centred = 0;  ///< of those, coned from a point inside S: cut again
  /// Partial tets the blade only grazes (its share S of the section has no area): split welded.
  std::int64_t tets_grazed = 0;
  /// Partial tets whose crack misses part of S (no apex touches every front side, or no end of
  /// S's sides on the faces opens). With the second pass: first pass's plus second's, an upper
  /// bound (the second pass may open what the first left short).
  std::int64_t tets_short = 0;
  std::int64_t second_pass_tets = 0;       ///< tets the second pass cut (mostly first-pass pieces)
  std::int64_t second_pass_originals = 0;  ///< of those, tets of the mesh before the cut
  std::int64_t second_pass_failed = 0;     ///< 1 when the second pass could not be composed
  std::int64_t tets_removed = 0;  ///< = split + relabelled + partial + second_pass_originals
  std::int64_t tets_added = 0;
  std::int64_t nodes_added = 0;
  std::int64_t edge_pairs = 0;         ///< opened cut edges (two nodes each)
  std::int64_t edge_singles = 0;       ///< welded cut edges (one node each)
  std::int64_t clones = 0;             ///< coplanar nodes cloned
  std::int64_t clones_on_outline = 0;  ///< of those, on the blade's outline (a crack front)
  std::int64_t steiner_points = 0;     ///< Schönhardt prisms and the apexes of partial tets
  std::int64_t face_points = 0;        ///< where the blade's outline crosses a tet face
  std::int64_t degenerate_tets = 0;    ///< emitted tets with non-positive rest volume (must be 0)
  double tolerance_m = 0.0;            ///< the classification tolerance used
  std::array<std::int64_t, 81> per_code{};  ///< candidates per sign case (case_code)
  std::array<std::int64_t, kNumCanonicalCases> per_case{};        ///< candidates per canonical case
  std::array<std::int64_t, kNumCanonicalCases> split_per_case{};  ///< split/relabelled per case
};

struct CutResult {
  TopologyDelta delta;  ///< apply(mesh, delta) performs the cut
  CutStats stats;
};

/// Candidate search: appends to `out` the ids of every tet whose current-position bounding box
/// meets the box [lo, hi] (m). It may report more tets, never fewer.
using TetBoxQuery =
    std::function<void(const Vec3& lo, const Vec3& hi, std::vector<std::int32_t>& out)>;

/// Brute-force TetBoxQuery over all tets of `mesh` (current positions).
[[nodiscard]] TetBoxQuery brute_force_query(const TetMesh& mesh);

}  // namespace serosa::cutting
