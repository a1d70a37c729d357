// Partial cuts (docs/cutting.md, point 5, the paper's end cases): a straddling tet whose section
// the blade covers only partly is cut along S = section ∩ blade, by coning every piece from one
// apex on the crack's front. This is the analysis: the section, the face points where the
// blade's outline crosses it, S, the apex, and whether the tet must be pinned instead.
#pragma once

#include <vector>

#include "cutting/cut_state.h"

namespace serosa::cutting::detail {

/// The section of straddling tet t: its vertices, in counter-clockwise order in the plane.
[[nodiscard]] std::vector<SecVert> section(const CutState& cs, const Tet& t, const TetInfo& info);

/// Sorted node ids of the face holding section vertices u and w; {-1,..} entries when they
/// share only an edge (two coplanar nodes); {-2,-2,-2} when they share no face.
[[nodiscard]] FaceKey face_key_of(const SecVert& u, const SecVert& w);

/// The (welded) node of face point fp, created on first use.
std::int32_t face_point_id(CutState& cs, FacePoint& fp);

/// A straddling tet that is not complete: finds the face points on its faces, whether the
/// blade meets it at all, and where the crack's front runs inside it: S = section ∩ blade is
/// opened by coning every piece from one apex on the front (the midpoint of a single chord, or
/// the blade's corner where two chords meet), so the crack is exactly the fan from the apex
/// over S's sides on the tet's faces. Fronts that no single point touches (two chords apart,
/// or two of the blade's corners inside) get the apex whose fan covers most of S.
void analyse_partial(CutState& cs, const Tet& t, TetInfo& info);

/// Partial tet, not pinned: whether its crack (the fan from the apex over S's runs with an end
/// that opens) misses part of S. After decide_edges and decide_clones.
[[nodiscard]] bool crack_short(const CutState& cs, const TetInfo& info);

}  // namespace serosa::cutting::detail
