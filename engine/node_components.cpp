#include "engine/node_components.h"

#include <numeric>

namespace serosa {

std::vector<std::int32_t> node_components(const TetMesh& mesh,
                                          const std::function<bool(std::size_t tet)>& keep) {
  std::vector<std::int32_t> parent(static_cast<std::size_t>(mesh.num_nodes()));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](std::int32_t a) {
    while (parent[static_cast<std::size_t>(a)] != a) {
      const auto ua = static_cast<std::size_t>(a);
      a = parent[ua] = parent[static_cast<std::size_t>(parent[ua])];
    }
    return a;
  };
  std::vector<char> used(parent.size(), 0);
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (keep && !keep(t)) continue;
    const Tet& tet = mesh.tets[t];
    for (int k = 0; k < 4; ++k) used[static_cast<std::size_t>(tet[k])] = 1;
    for (int k = 1; k < 4; ++k) parent[static_cast<std::size_t>(find(tet[k]))] = find(tet[0]);
  }
  std::vector<std::int32_t> label(parent.size(), -1), out(parent.size(), -1);
  std::int32_t next = 0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (keep && !keep(t)) continue;
    std::int32_t& l = label[static_cast<std::size_t>(find(mesh.tets[t][0]))];
    if (l < 0) l = next++;
  }
  for (std::size_t v = 0; v < parent.size(); ++v)
    if (used[v] != 0) out[v] = label[static_cast<std::size_t>(find(static_cast<std::int32_t>(v)))];
  return out;
}

}  // namespace serosa
