#include "fem/fem_elements.h"
#include "fem/parallel.h"

#include <stdexcept>
#include <vector>

namespace serosa::fem {
namespace {

TetElement element_of(const TetMesh& mesh, std::int32_t t, const FemConfig& config) {
  const Tet& n = mesh.tets[static_cast<std::size_t>(t)];
  TetElement e = make_element(mesh.rest[n[0]], mesh.rest[n[1]], mesh.rest[n[2]], mesh.rest[n[3]],
                              config.material(mesh.group[static_cast<std::size_t>(t)]));
  e.nodes = n;
  return e;
}

// Adds sign * (rho V / 4) and sign * (alpha rho V / 4) of element e to its nodes.
void lump(const Tet& nodes, const TetElement& e, double sign, FemElements& out) {
  const double m = sign * 0.25 * e.mass_kg;
  for (std::int32_t i : nodes) {
    out.node_mass[static_cast<std::size_t>(i)] += m;
    out.node_damping[static_cast<std::size_t>(i)] += e.alpha_hz * m;
  }
}

// Pieces connected through shared nodes: a component id per node (union-find roots).
std::vector<std::int32_t> node_components(const TetMesh& mesh) {
  std::vector<std::int32_t> parent(static_cast<std::size_t>(mesh.num_nodes()));
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<std::int32_t>(i);
  const auto find = [&](std::int32_t a) {
    while (parent[static_cast<std::size_t>(a)] != a)
      a = parent[static_cast<std::size_t>(a)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
    return a;
  };
  for (const Tet& t : mesh.tets)
    for (int k = 1; k < 4; ++k) parent[static_cast<std::size_t>(find(t[k]))] = find(t[0]);
  for (std::size_t i = 0; i < parent.size(); ++i) parent[i] = find(static_cast<std::int32_t>(i));
  return parent;
}

// Leaves the elements of every piece lighter than kDebrisVolumeM3 inactive, its nodes massless.
void deactivate_debris(const TetMesh& mesh, FemElements& out) {
  const std::vector<std::int32_t> comp = node_components(mesh);
  std::vector<double> volume(comp.size(), 0.0);  // per root
  for (std::size_t t = 0; t < mesh.tets.size(); ++t)
    volume[static_cast<std::size_t>(comp[static_cast<std::size_t>(mesh.tets[t][0])])] +=
        mesh.rest_volume(static_cast<std::int32_t>(t));
  out.debris_tets = 0;
  out.debris_volume_m3 = 0.0;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    const auto root = static_cast<std::size_t>(comp[static_cast<std::size_t>(mesh.tets[t][0])]);
    if (volume[root] >= kDebrisVolumeM3) continue;
    TetElement& e = out.elements[t];
    ++out.debris_tets;
    out.debris_volume_m3 += mesh.rest_volume(static_cast<std::int32_t>(t));
    if (!e.active()) continue;
    lump(e.nodes, e, -1.0, out);
    e.volume_m3 = 0.0;
    e.mass_kg = 0.0;
    for (std::int32_t i : e.nodes) {  // exactly massless, not round-off
      out.node_mass[static_cast<std::size_t>(i)] = 0.0;
      out.node_damping[static_cast<std::size_t>(i)] = 0.0;
    }
  }
}

}  // namespace

void build_elements(const TetMesh& mesh, const FemConfig& config, FemElements& out) {
  const auto m = static_cast<std::size_t>(mesh.num_tets());
  out.elements.resize(m);
#pragma omp parallel for schedule(static) if (mesh.num_tets() >= kParallelMin)
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t)
    out.elements[static_cast<std::size_t>(t)] = element_of(mesh, t, config);
  out.node_mass.assign(static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  out.node_damping.assign(static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  for (std::size_t t = 0; t < m; ++t) lump(mesh.tets[t], out.elements[t], 1.0, out);
  deactivate_debris(mesh, out);
  out.topology_version = mesh.topology_version;
}

void update_elements(const TetMesh& mesh, const TopologyDelta& delta, const FemConfig& config,
                     FemElements& out) {
  if (out.topology_version != delta.version_before || mesh.topology_version != delta.version_after)
    throw std::logic_error("update_elements: delta does not follow the elements' version");
  // 1. Removed tets give back their mass (each element remembers its node ids; apply() only
  //    appends nodes, so old ids stay valid).
  std::vector<std::pair<std::int32_t, double>> drained;  // (node, mass removed from it) kg
  for (std::int32_t r : delta.removed_tets) {
    const TetElement& e = out.elements[static_cast<std::size_t>(r)];
    lump(e.nodes, e, -1.0, out);
    for (std::int32_t i : e.nodes) drained.emplace_back(i, 0.25 * e.mass_kg);
  }
  // 2. New nodes start massless.
  out.node_mass.resize(static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  out.node_damping.resize(static_cast<std::size_t>(mesh.num_nodes()), 0.0);
  // 3. Added tets go to their slots (reused holes first, then appended in order).
  for (std::size_t k = 0; k < delta.slot_of_added.size(); ++k) {
    const auto slot = static_cast<std::size_t>(delta.slot_of_added[k]);
    if (slot >= out.elements.size()) out.elements.resize(slot + 1);
    out.elements[slot] = element_of(mesh, delta.slot_of_added[k], config);
    lump(out.elements[slot].nodes, out.elements[slot], 1.0, out);
  }
  // 4. Replay the relabels in order, then drop the tail.
  for (const auto& [from, to] : delta.moved_tets)
    out.elements[static_cast<std::size_t>(to)] = out.elements[static_cast<std::size_t>(from)];
  out.elements.resize(static_cast<std::size_t>(mesh.num_tets()));
  // Round-off of the subtraction: a node that lost all its tets keeps |m| ~ 1e-16 of what it lost.
  for (const auto& [i, lost] : drained) {
    auto& m = out.node_mass[static_cast<std::size_t>(i)];
    if (m < 1e-12 * lost) {
      m = 0.0;
      out.node_damping[static_cast<std::size_t>(i)] = 0.0;
    }
  }
  deactivate_debris(mesh, out);
  out.topology_version = mesh.topology_version;
}

}  // namespace serosa::fem
