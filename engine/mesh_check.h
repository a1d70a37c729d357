// check_mesh: counts, volumes, quality and the structural invariants of a tet mesh, in one report
// (serosa check, and tests after cuts). It never throws on a bad mesh: it says what is wrong.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "engine/math.h"
#include "engine/tet_mesh.h"

namespace serosa {

struct MeshCheckOptions {
  /// A tet whose |rest volume| is at most this fraction of (mean edge length)^3 is flat (same
  /// rule as MeshReadOptions::flat_tolerance).
  double flat_tolerance = 1e-12;
  /// Where each tet came from, for the messages: (m) its 1-based line in `tet_file`
  /// (MeshReadReport::tet_lines); empty: tets are named by their index only.
  std::vector<std::int64_t> tet_lines;
  std::vector<std::int64_t> tet_ids;  ///< (m) the file's element id of each tet, with tet_lines
  std::string tet_file;
};

/// What check_mesh found. Geometry is the rest configuration. Messages name tets and nodes by
/// their 0-based index in the mesh arrays (file order; non-tet elements do not count), and a tet
/// by its line in the file too when the options give the lines. Tets with a
/// node id out of range or touching a non-finite node are left out of volumes and qualities (and
/// counted as such).
struct MeshCheckReport {
  std::int64_t nodes = 0;                  ///< n
  std::int64_t tets = 0;                   ///< m
  double volume_m3 = 0.0;                  ///< sum of signed rest volumes, m^3
  std::map<int, double> group_volume_m3;   ///< group -> sum of signed rest volumes, m^3
  std::map<int, std::int64_t> group_tets;  ///< group -> number of tets
  Vec3 bbox_min = Vec3::Zero();            ///< smallest rest coordinates of finite nodes, m
  Vec3 bbox_max = Vec3::Zero();            ///< largest rest coordinates of finite nodes, m
  double min_quality = 0.0;     ///< smallest mean-ratio quality (engine/mesh_quality.h); 0 if none
  double median_quality = 0.0;  ///< median mean-ratio quality; 0 if no tets
  std::int64_t inverted_tets = 0;       ///< negative volume (and not flat)
  std::int64_t flat_tets = 0;           ///< |volume| within flat_tolerance (repeated nodes too)
  std::int64_t duplicate_tets = 0;      ///< tets with the same node set as an earlier tet
  std::int64_t boundary_faces = 0;      ///< faces used by exactly one tet
  std::int64_t interior_faces = 0;      ///< faces shared by exactly two tets
  std::int64_t overshared_faces = 0;    ///< faces shared by three or more tets
  std::int64_t misoriented_faces = 0;   ///< faces shared by two tets lying on the same side of it
  std::int64_t unreferenced_nodes = 0;  ///< nodes used by no tet (a warning, not a problem)
  std::int64_t nonfinite_nodes = 0;     ///< nodes with a NaN or infinite rest coordinate
  std::int64_t bad_tets = 0;            ///< tets with a node id out of [0, n)
  bool valid = false;                   ///< true when `problems` is empty
  std::vector<std::string> problems;    ///< what makes the mesh unusable, one sentence each
  std::vector<std::string> warnings;    ///< what is odd but usable
};

/// Checks `mesh`. A mesh is valid when it has tets, consistent array sizes, every node id in
/// range, finite coordinates, no inverted, flat or duplicated tets, no face shared by more than
/// two tets and no face shared by two tets on the same side of it.
[[nodiscard]] MeshCheckReport check_mesh(const TetMesh& mesh, const MeshCheckOptions& options = {});

}  // namespace serosa
