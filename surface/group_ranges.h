// Group ranges from per-group face counts (both extraction back ends use it).
#pragma once

#include <cstddef>
#include <cstdint>

#include "surface/surface_mesh.h"

namespace serosa::surface {

/// Sets s.groups from n group ids (ascending) and their face counts: offsets are running sums.
inline void set_group_ranges(SurfaceMesh& s, const std::uint16_t* ids, const std::int32_t* counts,
                             std::size_t n) {
  s.groups.resize(n);
  std::int32_t offset = 0;
  for (std::size_t i = 0; i < n; ++i) {
    s.groups[i] = GroupRange{ids[i], offset, counts[i]};
    offset += counts[i];
  }
}

}  // namespace serosa::surface
