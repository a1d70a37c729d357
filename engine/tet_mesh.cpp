#include "engine/tet_mesh.h"

namespace serosa {

std::int32_t TetMesh::add_node(const Vec3& p) {
  rest.push_back(p);
  x.push_back(p);
  v.push_back(Vec3::Zero());
  mass.push_back(0.0);
  fixed.push_back(0);
  return num_nodes() - 1;
}

std::int32_t TetMesh::add_tet(const Tet& t, std::uint16_t g) {
  tets.push_back(t);
  group.push_back(g);
  return num_tets() - 1;
}

void TetMesh::fill_node_state() {
  const std::size_t n = rest.size();
  const std::size_t old = x.size();
  x.resize(n);
  for (std::size_t i = old; i < n; ++i) x[i] = rest[i];
  v.resize(n, Vec3::Zero());
  mass.resize(n, 0.0);
  fixed.resize(n, 0);
}

double TetMesh::rest_volume(std::int32_t i) const {
  const Tet& t = tets[i];
  return signed_volume(rest[t[0]], rest[t[1]], rest[t[2]], rest[t[3]]);
}

}  // namespace serosa
