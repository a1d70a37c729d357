// Shared by the mesh reader fuzzers: a mesh that was read must satisfy every invariant the readers
// promise; anything else aborts so that libFuzzer reports it. Only InputError may escape a reader.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "engine/tet_mesh.h"

namespace serosa::fuzz {

inline void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "invariant violated: %s\n", what);
    std::abort();
  }
}

inline void check_mesh(const TetMesh& m) {
  const auto n = m.rest.size();
  require(n > 0 && m.num_tets() > 0, "non-empty mesh");
  require(m.x.size() == n && m.v.size() == n && m.mass.size() == n && m.fixed.size() == n,
          "node arrays sized");
  require(m.group.size() == m.tets.size(), "one group per tet");
  for (const Vec3& p : m.rest) require(p.allFinite(), "finite positions");
  for (std::int32_t k = 0; k < m.num_tets(); ++k) {
    for (const std::int32_t id : m.tets[static_cast<std::size_t>(k)]) {
      require(id >= 0 && id < m.num_nodes(), "node ids in range");
    }
    const double v = m.rest_volume(k);
    require(std::isfinite(v) && v > 0.0, "positive volume");
  }
}

}  // namespace serosa::fuzz
