// remove_cut: the element-removal baseline. Every tet the blade polygon
// touches is dropped, nothing is subdivided and no node is created or moved. Same interface as
// cut_mesh (a CutResult whose TopologyDelta engine's apply() performs), so the three methods can be
// compared on the same blades (cutting/cut_method.h).
//
// What it does not keep (by design, it is the cheap baseline): volume (the removed tets are lost),
// the blade's path (the new boundary is the faces of the neighbours, up to one tet away from the
// polygon), and the nodes of removed tets that no remaining tet uses stay in the mesh unreferenced
// (a TopologyDelta cannot remove nodes; they carry no tet, so FEM gives them no stiffness).
#pragma once

#include "cutting/convex_polygon.h"
#include "cutting/cut_mesh.h"
#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa::cutting {

/// True when the closed tet (a, b, c, d) meets the closed polygon `blade`, both grown by tol (m):
/// the tet's section by the blade's plane (nodes within tol of the plane count as on it) and the
/// polygon overlap in the plane (separating-axis test on the two convex outlines). Exact up to tol;
/// a tet that only touches the polygon (a node, an edge or a face on it) counts as touching.
/// @param a,b,c,d node positions, m
[[nodiscard]] bool tet_touches_polygon(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                                       const ConvexPolygon& blade, double tol = 0.0);

/// Removes every tet of `mesh` (current positions x) that `blade` touches (tet_touches_polygon
/// with tol = options.classify_rel * h, h the longest edge of the tets whose boxes meet the blade's
/// box). The delta only removes tets. Stats: candidates, tets_removed, tolerance_m (the other
/// counts are 0). `query` finds candidate tets (a BVH; brute force when empty).
[[nodiscard]] CutResult remove_cut(const TetMesh& mesh, const ConvexPolygon& blade,
                                   const CutOptions& options = {}, const TetBoxQuery& query = {});

}  // namespace serosa::cutting
