// Incremental boundary update from a TopologyDelta: only the faces of removed,
// added and moved tets are looked at, and the result equals a full extraction (same oriented
// faces with the same tets in the same groups; the order inside a group may differ).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/tet_mesh.h"
#include "engine/topology_delta.h"
#include "surface/cut_faces.h"
#include "surface/face_key.h"
#include "surface/face_map.h"
#include "surface/surface_mesh.h"

namespace serosa::surface {

/// The surface consumer's private bookkeeping (the SurfaceMesh itself stays plain data to copy and
/// publish). Holds node ids only, never positions.
struct FaceTable {
  using Entry = FaceEntry;
  FaceMap faces;                ///< every face of every tet
  std::vector<WideKey> key_at;  ///< (f) key of each SurfaceMesh face
  /// (m) the tets' node ids, kept in step with the mesh: a delta names removed tets by id only,
  /// and apply() has overwritten them by the time the consumer runs.
  std::vector<Tet> tets;
};

/// Builds the table for `mesh` and its full extraction `s` (extract_surface(mesh)). O(m).
/// Throws std::invalid_argument when s is not mesh's boundary.
[[nodiscard]] FaceTable build_face_table(const TetMesh& mesh, const SurfaceMesh& s);

/// Updates `s` and `table` for `delta`, already applied (engine apply()) to the mesh now `after`.
/// Cost: O((removed + added + moved tets) x (1 + number of groups)) hash lookups. Faces keep their
/// slots unless their group's range must grow or shrink; each group stays one contiguous range,
/// groups ascending; empty groups are dropped and new ones inserted in order.
/// face_cut of each new face follows surface/cut_faces.h against `original` (0 when null), so
/// that it equals extract_surface(after, *original) face for face; faces that only change owner
/// keep their flag (it depends on nodes and group only).
/// changed_slots (optional, out): the slots of `s` written by this update (new faces, faces moved
/// into another slot, faces whose owner or orientation changed), ascending, unique, all below
/// s.num_faces(); slots at or past the old face count are always listed. With the new face count,
/// that is all a consumer keyed by slot (SurfaceBvh::update) needs.
/// Throws std::invalid_argument when the delta does not follow on from `s` (versions or sizes);
/// `s` and `table` are then unspecified: rebuild them with extract_surface and build_face_table.
void update_surface(SurfaceMesh& s, FaceTable& table, const TetMesh& after,
                    const TopologyDelta& delta, const OriginalSurface* original = nullptr,
                    std::vector<std::int32_t>* changed_slots = nullptr);

}  // namespace serosa::surface
