// Cut faces: which boundary faces a cut made (the wound), and which lie on the
// organ's original surface.
//
// The rule, the same for full extraction and incremental update so that both give equal flags:
//   a boundary face of group g is ORIGINAL (face_cut = 0) when, in rest coordinates
//   (TetMesh::rest), all three of its nodes lie on one triangle of the original surface of the
//   same group g (within 1e-6 of that triangle's longest edge); otherwise it is CUT (1).
// Why this is sound: a cut never moves nodes, and its patterns subdivide faces exactly (new nodes
// are interpolated on edges, faces or inside tets of the rest mesh), so every piece of an original
// face lies in that face's plane and inside it; a face created on the blade, or exposed by removing
// tets, lies inside the organ and hence on no original triangle. The flag is a pure function of
// the face's rest geometry, its group and the reference, so it needs no history and both paths
// agree by construction. Limits: a blade lying within the tolerance of the original surface
// (grazing the skin tangentially) makes faces that count as original; a mesh that was already cut
// when the reference was taken treats its wounds as original surface.
//
// The reference, OriginalSurface, is the boundary at load time (before any cut) in rest
// coordinates, with a uniform hash grid over its triangles; rest positions never change, so it is
// built once per organ. Without a reference, every face counts as original (face_cut = 0).
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "engine/tet_mesh.h"
#include "surface/surface_mesh.h"

namespace serosa::surface {

/// The uncut boundary of an organ in rest coordinates: the reference of the cut-face rule above.
/// Immutable after construction; holds positions copied from TetMesh::rest, which never change
/// for existing nodes (cuts only add nodes).
class OriginalSurface {
 public:
  OriginalSurface() = default;
  /// From `s`, the boundary of `mesh` (extract_surface(mesh)) before any cut.
  /// Throws std::invalid_argument when s names nodes `mesh` does not have.
  OriginalSurface(const TetMesh& mesh, const SurfaceMesh& s);

  /// True when the triangle with rest corners (a, b, c) (m) in group g lies on one original
  /// triangle of group g (every corner within tolerance of it).
  [[nodiscard]] bool contains(const Vec3& a, const Vec3& b, const Vec3& c, std::uint16_t g) const;

  [[nodiscard]] bool empty() const { return tris_.empty(); }
  [[nodiscard]] std::size_t size() const { return tris_.size(); }

 private:
  [[nodiscard]] std::uint64_t cell_key(const Vec3& p) const;

  std::vector<std::array<Vec3, 3>> tris_;  ///< (o) rest corners, m
  std::vector<std::uint16_t> group_;       ///< (o) group of each
  std::vector<double> tol2_;               ///< (o) squared tolerance, m^2
  Vec3 origin_ = Vec3::Zero();             ///< grid origin (box corner), m
  double cell_ = 1.0;                      ///< grid cell edge, m
  /// cell key -> [begin, end) in cell_tris_
  std::unordered_map<std::uint64_t, std::pair<std::int32_t, std::int32_t>> cells_;
  std::vector<std::int32_t> cell_tris_;  ///< original triangles per cell, grouped by cell
};

/// Face_cut of one face (node ids `f`, group g) of `mesh`: 1 when cut, 0 when original (rule
/// above; 0 for every face when `original` is empty).
[[nodiscard]] std::uint8_t classify_face(const Tri& f, std::uint16_t g, const TetMesh& mesh,
                                         const OriginalSurface& original);

/// Sets s.face_cut (f) for every face of `s`, the boundary of `mesh`.
void mark_cut_faces(SurfaceMesh& s, const TetMesh& mesh, const OriginalSurface& original);

}  // namespace serosa::surface
