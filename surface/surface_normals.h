// Render vertices and per-vertex normals of a SurfaceMesh: area-weighted normals
// per corner, split across cut edges (where a wound face meets an original one), across creases
// sharper than a set angle, and between groups (each visual mesh has its own vertices).
//
// A render vertex is one (node, normal cluster) pair. Around a node, two faces that share an edge
// through that node are in the same cluster when the edge is smooth: exactly two faces use it,
// both have the same face_cut and group, and the angle between their normals is at most the
// crease angle. Clusters are the connected sets of faces around the node under that relation (a
// node's faces fan around it, so a crease splits the fan; a smooth fan, closed or open, is one
// cluster). The cluster's normal is the sum of its faces' (b - a) x (c - a), i.e. area-weighted,
// normalised.
#pragma once

#include <cstdint>
#include <numbers>
#include <span>
#include <vector>

#include "engine/math.h"
#include "surface/surface_mesh.h"

namespace serosa::surface {

struct NormalOptions {
  /// Edges whose two faces' normals differ by more than this angle (rad) split normals.
  double crease_angle_rad = std::numbers::pi / 3.0;  // 60 degrees
  bool split_cut_edges = true;                       ///< split where face_cut differs (wound edge)
  bool split_groups = true;  ///< split where face_group differs (visual meshes apart)
};

/// Vertices for drawing a SurfaceMesh. Positions are not copied: render vertex i sits at
/// TetMesh::x[node[i]] (one set of nodes); `tris` indexes the render vertices face for face.
struct RenderVertices {
  std::vector<std::int32_t> node;  ///< (v) TetMesh node id of each render vertex
  std::vector<Vec3> normal;        ///< (v) unit outward normal (current positions)
  /// (f) render vertex of each corner of SurfaceMesh face i, same corner order (counter-clockwise
  /// from outside), so SurfaceMesh::groups ranges apply to it unchanged.
  std::vector<Tri> tris;
};

/// Builds render vertices and normals of `s` in positions `x` ((n) TetMesh::x, m). Vertices are
/// ordered by node id, then by the first face corner of their cluster (deterministic). A cluster
/// whose faces all have zero area gets the area-weighted normal of all the node's faces, or
/// +z if that is zero too. O(f log f). Throws std::invalid_argument when s.face_cut or
/// s.face_group are not sized like s.faces or a face names a node outside x.
void compute_render_vertices(const SurfaceMesh& s, std::span<const Vec3> x,
                             const NormalOptions& options, RenderVertices& out);

}  // namespace serosa::surface
