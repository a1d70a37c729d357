#include "engine/topology_delta.h"

#include <stdexcept>
#include <string>

#include "engine/tet_mesh.h"

namespace serosa {
namespace {

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("TopologyDelta: " + what);
}

// Validates the whole delta against the mesh before anything is written.
void validate(const TetMesh& mesh, const TopologyDelta& d) {
  const std::int32_t m = mesh.num_tets();
  const std::int32_t n_old = mesh.num_nodes();
  const auto n_new = n_old + static_cast<std::int32_t>(d.added_nodes.size());
  check(d.added_groups.size() == d.added_tets.size(), "added_groups and added_tets differ in size");
  for (std::size_t i = 0; i < d.removed_tets.size(); ++i) {
    const std::int32_t t = d.removed_tets[i];
    check(t >= 0 && t < m, "removed tet " + std::to_string(t) + " out of range");
    check(i == 0 || d.removed_tets[i - 1] < t, "removed_tets not sorted and unique");
  }
  for (const NodeParent& p : d.added_nodes) {
    check(p.count >= 1 && p.count <= 4, "node parent count not in 1..4");
    double sum = 0.0;
    for (int k = 0; k < p.count; ++k) {
      check(p.nodes[k] >= 0 && p.nodes[k] < n_old, "node parent id out of range");
      sum += p.weights[k];
    }
    check(std::abs(sum - 1.0) < 1e-9, "node parent weights do not sum to 1");
  }
  for (const Tet& t : d.added_tets)
    for (std::int32_t id : t) check(id >= 0 && id < n_new, "added tet node id out of range");
}

}  // namespace

void apply(TetMesh& mesh, TopologyDelta& d) {
  validate(mesh, d);
  d.version_before = mesh.topology_version;

  // 1. New nodes, interpolated from their parents.
  for (const NodeParent& p : d.added_nodes) {
    Vec3 r = Vec3::Zero(), x = Vec3::Zero(), v = Vec3::Zero();
    for (int k = 0; k < p.count; ++k) {
      r += p.weights[k] * mesh.rest[p.nodes[k]];
      x += p.weights[k] * mesh.x[p.nodes[k]];
      v += p.weights[k] * mesh.v[p.nodes[k]];
    }
    const std::int32_t id = mesh.add_node(r);
    mesh.x[id] = x;
    mesh.v[id] = v;
  }

  // 2.-3. Added tets reuse removed slots in order, the rest are appended.
  d.slot_of_added.clear();
  d.moved_tets.clear();
  const std::size_t reuse = std::min(d.removed_tets.size(), d.added_tets.size());
  for (std::size_t k = 0; k < d.added_tets.size(); ++k) {
    if (k < reuse) {
      const std::int32_t slot = d.removed_tets[k];
      mesh.tets[slot] = d.added_tets[k];
      mesh.group[slot] = d.added_groups[k];
      d.slot_of_added.push_back(slot);
    } else {
      d.slot_of_added.push_back(mesh.add_tet(d.added_tets[k], d.added_groups[k]));
    }
  }

  // 4. Leftover holes (largest first) are filled by the last tet, unless the hole is the last.
  for (std::size_t k = d.removed_tets.size(); k-- > reuse;) {
    const std::int32_t hole = d.removed_tets[k];
    const std::int32_t last = mesh.num_tets() - 1;
    if (hole != last) {
      mesh.tets[hole] = mesh.tets[last];
      mesh.group[hole] = mesh.group[last];
      d.moved_tets.emplace_back(last, hole);
    }
    mesh.tets.pop_back();
    mesh.group.pop_back();
  }

  ++mesh.topology_version;
  d.version_after = mesh.topology_version;
}

}  // namespace serosa
