#include "engine/boundary.h"

#include <algorithm>
#include <tuple>

#include "engine/tet_faces.h"

namespace serosa {

namespace {

// Rotates a face (keeping its winding) so that it starts at its smallest node id: one canonical
// spelling per oriented face, so results compare equal across implementations.
Tri rotate_to_min(const Tri& f) {
  const auto it = std::min_element(f.begin(), f.end());
  const auto s = static_cast<std::size_t>(it - f.begin());
  return {f[s], f[(s + 1) % 3], f[(s + 2) % 3]};
}

}  // namespace

FaceCensus face_census(const TetMesh& mesh) {
  FaceCensus census;
  const std::vector<TetFace> faces = sorted_tet_faces(mesh.tets);

  // Walk runs of equal keys: a run of 1 is boundary, 2 interior, 3 or more overshared.
  std::size_t i = 0;
  while (i < faces.size()) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    const std::size_t count = j - i;
    if (count == 1) {
      const TetFace& f = faces[i];
      BoundaryFace b;
      b.nodes = rotate_to_min(tet_face(mesh.tets[static_cast<std::size_t>(f.tet)], f.local));
      b.tet = f.tet;
      // A group array shorter than the tets (a malformed mesh) reads as group 0.
      b.group = static_cast<std::size_t>(f.tet) < mesh.group.size()
                    ? mesh.group[static_cast<std::size_t>(f.tet)]
                    : std::uint16_t{0};
      census.boundary.push_back(b);
    } else if (count == 2) {
      ++census.interior;
    } else {
      ++census.overshared;
    }
    i = j;
  }

  // faces are sorted by key already; a stable sort by group gives (group, key) order.
  std::stable_sort(census.boundary.begin(), census.boundary.end(),
                   [](const BoundaryFace& a, const BoundaryFace& b) { return a.group < b.group; });
  return census;
}

}  // namespace serosa
