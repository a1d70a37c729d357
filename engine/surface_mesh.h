// SurfaceMesh: the boundary surface of a TetMesh, grouped by visual mesh (paper, "Surface
// extraction"; docs/ARCHITECTURE.md "Data model").
#pragma once

#include <cstdint>
#include <vector>

#include "engine/math.h"

namespace serosa {

/// One visual mesh's faces: SurfaceMesh::faces[offset, offset + count).
struct GroupRange {
  std::uint16_t group = 0;  ///< the tets' group (Gmsh physical tag)
  std::int32_t offset = 0;  ///< first face of the group
  std::int32_t count = 0;   ///< number of faces, > 0
};

/// The boundary triangles of a tet mesh: every face used by exactly one tet. Faces reference
/// TetMesh node ids (never copies of positions), so collision and rendering read the mechanical
/// nodes themselves. Faces of one group are contiguous; `groups` lists the groups that have
/// faces, by ascending group id, so that each visual mesh is one range of the buffers.
struct SurfaceMesh {
  std::vector<Tri> faces;                 ///< (f) node ids, counter-clockwise seen from outside
  std::vector<std::int32_t> face_tet;     ///< (f) the tet each face belongs to
  std::vector<std::uint16_t> face_group;  ///< (f) that tet's group
  std::vector<std::uint8_t> face_cut;     ///< (f) 1 = made by a cut (wound), 0 = original surface
                                          ///< (rule: surface/cut_faces.h)
  std::vector<GroupRange> groups;         ///< (g) ascending group id, ranges tile [0, f)
  std::uint64_t topology_version = 0;     ///< TetMesh::topology_version it was extracted from

  [[nodiscard]] std::int32_t num_faces() const { return static_cast<std::int32_t>(faces.size()); }
};

}  // namespace serosa
