// Coplanar faces and edges under the blade's outline (docs/cutting.md, point 5, "coplanar
// faces partly under the blade"): a welded face in the plane that the blade covers only partly
// is clipped along the outline, so a scissors closing in steps thinner than the mesh's faces
// opens the crack step by step. The outline's crossings of the clipped faces' edges (and of the
// coplanar edges partial tets stop the crack on) become welded nodes that every tet around the
// edge splits at; the part of a clipped face under the blade is fanned from an opened pair of
// nodes at its centroid.
#pragma once

#include <vector>

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// Points where the outline crosses coplanar edge (a, b), computed once per edge.
std::vector<CopPoint>& cop_edge(CutState& cs, std::int32_t a, std::int32_t b);
/// The crossings of coplanar edge (a, b) decide_faces kept (empty for other edges).
std::vector<CopPoint>& cop_points(CutState& cs, std::int32_t a, std::int32_t b);
[[nodiscard]] bool has_cop_points(const CutState& cs, std::int32_t a, std::int32_t b);
/// The (welded) node of crossing p, created on first use.
std::int32_t cop_point_id(CutState& cs, CopPoint& p);

/// Coplanar faces of the candidates (a face two candidates share is still welded; one a single
/// candidate holds is already open or on the surface); the welded ones the blade covers only
/// partly (with positive area) are clipped along its outline: their edges get the outline's
/// crossings, and every tet around such an edge is split there; so are the coplanar edges along
/// partial tets' sections that the outline crosses (classify). After classify.
void decide_faces(CutState& cs);

/// Clipped face `key` (in pfaces) seen from its node a: its corner at a lies under the blade
/// (the midpoints from a to the next point along both edges from a are inside), so every piece
/// of the face at a is under the blade and a may open.
[[nodiscard]] bool corner_inside(const CutState& cs, std::int32_t a, const FaceKey& key);

/// A one-sided tet holding a clipped coplanar face or a coplanar edge with crossings: it is
/// split there (coned from its off-plane node, or fanned from its opposite edge), welded except
/// the clipped part under the blade.
[[nodiscard]] bool needs_cop_split(const CutState& cs, const Tet& t, const TetInfo& info);
/// Emits the pieces of such a tet, in group g.
void emit_cop_split(CutState& cs, const Tet& t, const TetInfo& info, std::uint16_t g);

}  // namespace serosa::cutting::detail
